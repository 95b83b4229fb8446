#pragma once
// One run of a session, as the sidecar's `runs` records it (docs/adjustment-study.md, "What a
// session writes"): typed, so that the session fills in fields rather than JSON keys, and written
// in one place.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/append_file.h"

namespace countershade::runtime {

// How a run ended.
enum class RunEnd {
  running,           // not yet ended; a later resume finds it so and records `interrupted`
  completed,         // every answer given
  quit,              // the participant quit from the pause screen
  closed,            // the window was closed
  interrupted,       // SIGINT, or killed or crashed (found by the next resume)
  terminated,        // SIGTERM
  script_ended,      // a --script ran out of events
  already_complete,  // resumed with every answer already recorded
  display_failed,    // the window could not be opened
  error,             // an error stopped the run (SessionRun::error says which)
};
const char* run_end_name(RunEnd end);  // as the sidecar writes it: "completed", "script-ended", …

struct Pause {
  double at_s = 0, seconds = 0;
  bool quit = false;  // the run ended during the pause
};

struct FocusLoss {
  double at_s = 0;
  std::string utc;
};

struct Preload {
  size_t images = 0;
  double seconds = 0;
};

struct SessionRun {
  std::string started_utc, ended_utc;
  RunEnd end = RunEnd::running;
  std::string error;  // RunEnd::error: the message
  bool resumed = false;
  int answers_before = 0, answers = 0;  // rows in the CSV before this run, and rows this run added
  std::vector<Pause> pauses;
  std::vector<FocusLoss> focus_losses;
  std::optional<Preload> preload;
  nlohmann::ordered_json display;  // the presenter's own record (GL, screen, window)
  nlohmann::ordered_json frames;   // the frame statistics' own record
  std::optional<int> system_key_repeats_ignored;

  // The sidecar's entry: the fields in a fixed order, those not yet known left out.
  nlohmann::ordered_json to_json() const;
};

// Whether `runs` is a sidecar's list of runs: an array of objects.
bool is_run_list(const nlohmann::ordered_json& runs);

// Marks the runs of a sidecar's list that never recorded their end (killed, crashed, power
// lost) as `interrupted`; a resume does this before it adds its own run.
void mark_unended_runs_interrupted(nlohmann::ordered_json& runs);

// Opens one of a session's answer files (rows, trajectory) to resume it. A file that is missing
// or empty is begun with `header`: a kill right after the sidecar was written leaves it so. Where
// the sidecar's `runs` say rows were written to it, they are lost: that is refused (InputError).
AppendOnlyFile open_answers_to_resume(const std::filesystem::path& file, const std::string& header,
                                      const nlohmann::ordered_json& runs);

}  // namespace countershade::runtime
