#pragma once
// One run of an adjustment session: checks every input, plans the trials, opens the recorder,
// then the window; preloads the stimuli and runs the procedure until it is finished, quit,
// closed, or (for tests) the key script ends.

#include <filesystem>
#include <optional>
#include <string>

#include "runtime/fine_levels.h"

namespace countershade::adjust {

struct SessionOptions {
  std::filesystem::path manifest;
  std::optional<std::filesystem::path> config;  // --procedure
  std::string subject;
  int session = 1;
  std::filesystem::path sessions_dir = "sessions";
  bool resume = false;
  bool fullscreen = false;
  int monitor = 0;
  std::optional<std::filesystem::path> script;
  std::optional<std::filesystem::path> screenshot;
  std::optional<std::string> observer;  // "simulated:SEED"
  bool frame_clock = false;  // DisplayOptions::frame_clock (with a script or an observer)
  std::optional<double>
      monitor_width_mm;  // overrides the size the monitor reports (visual angle check)
  runtime::OutputPathChoice output_path;  // 16-bit sets: --output-path
  std::optional<uint32_t> dither_seed;    // default: the session seed
};

// Returns the exit status: 0 when the run ended normally (finished, quit and saved, closed or
// the script ended). Bad input throws InputError before any window opens.
int run_session(const SessionOptions& options);

}  // namespace countershade::adjust
