#pragma once
// One run of a forced-choice session (`countershade choose`): checks every input, opens the
// recorder, then the window; preloads the stimuli and shows trial after trial until the session
// is finished, quit, closed, or (for tests) the key script ends.

#include <filesystem>
#include <optional>
#include <string>

#include "runtime/fine_levels.h"

namespace countershade::forced_choice {

struct ChoiceSessionOptions {
  std::filesystem::path manifest;
  std::optional<std::filesystem::path>
      config;  // --procedure; else the experiment's "forced_choice"
  std::string subject;
  int session = 1;
  std::filesystem::path sessions_dir = "sessions";
  bool resume = false;
  bool fullscreen = false;
  int monitor = 0;
  std::optional<std::filesystem::path> script;
  std::optional<std::filesystem::path> screenshot;
  std::optional<std::string> observer;  // "weibull:ALPHA,BETA,SEED"
  bool frame_clock = false;
  runtime::OutputPathChoice output_path;  // 16-bit sets: --output-path
  std::optional<uint32_t> dither_seed;    // default: the session seed
};

// Returns 0 when the run ended normally. Bad input throws InputError before any window opens.
int run_choice_session(const ChoiceSessionOptions& options);

}  // namespace countershade::forced_choice
