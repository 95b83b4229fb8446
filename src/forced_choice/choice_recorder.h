#pragma once
// What a forced-choice session writes (docs/data-formats.md, "Forced-choice trials"):
//   SUBJECT_sNN.forced-choice.csv   one row per trial, appended with one write() and fsync'd
//                                   before the next trial appears;
//   SUBJECT_sNN.forced-choice.json  the sidecar: configuration, seed, set, and one entry per run.
// A new session never overwrites a file; a resume replays the rows through the session's
// ChoiceRun, checking each against what the run would have shown, so a resumed session goes on
// exactly where it stopped, with the procedures in the same state.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/append_file.h"
#include "forced_choice/choice_row.h"
#include "forced_choice/choice_run.h"
#include "runtime/session_run.h"
#include "runtime/study.h"

namespace countershade::forced_choice {

struct ChoiceFiles {
  std::filesystem::path csv, sidecar;
};
ChoiceFiles choice_files(const std::filesystem::path& dir, const std::string& subject, int session);

class ChoiceRecorder {
 public:
  struct Identity {
    std::string subject;
    int session = 1;
    uint64_t seed = 1;
  };

  // New session: creates both files (neither may exist), the sidecar first. Resume: the sidecar
  // must exist, with this session's seed and configuration; the rows are replayed into `run`
  // (a trials file that is missing or empty, as a kill right after the sidecar leaves it, is
  // begun with its header).
  ChoiceRecorder(const runtime::Study& study, const ChoiceConfig& config, const Identity& who,
                 const std::filesystem::path& dir, bool resume, ChoiceRun& run);

  // Appends the trial's row and fsyncs it before returning.
  void record(const ChoiceTrial& trial, int response, bool correct, double rt_s);
  runtime::SessionRun& current_run() { return run_; }
  int rows() const { return rows_; }
  const ChoiceFiles& files() const { return files_; }
  // Writes the sidecar, with each condition's procedure state after the last recorded trial.
  void save(const ChoiceRun& run);

 private:
  void begin_session(const ChoiceRun& run);
  void resume_session(ChoiceRun& run);
  void replay(ChoiceRun& run);

  const runtime::Study& study_;
  const ChoiceConfig& config_;
  Identity who_;
  ChoiceFiles files_;
  AppendOnlyFile csv_;
  nlohmann::ordered_json sidecar_;
  runtime::SessionRun run_;
  int rows_ = 0;
};

}  // namespace countershade::forced_choice
