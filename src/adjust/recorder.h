#pragma once
// Everything a session writes, so that no answer is ever lost:
//   SUBJECT_sNN.csv       the responses (docs/data-formats), one row per confirmed answer, each
//                         appended with one write() and fsync'd before the next stimulus appears;
//   SUBJECT_sNN.json      the sidecar: configuration, seed, plan, display, and one entry per run
//                         (start, end, pauses, focus losses, frame timing), replaced atomically;
//   SUBJECT_sNN.keys.tsv  the trajectory: every key event and λ step with its time (tab-separated).
// A new session never overwrites an existing file; --resume appends to the existing ones.

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "adjust/procedure.h"
#include "core/append_file.h"
#include "runtime/session_run.h"
#include "runtime/study.h"

namespace countershade::adjust {

struct SessionFiles {
  std::filesystem::path csv, sidecar, keys;
};
SessionFiles session_files(const std::filesystem::path& dir, const std::string& subject,
                           int session);

// What an existing session's CSV holds, mapped onto the plan.
struct RecordedAnswers {
  std::map<std::pair<int, int>, PastAnswer> answered;  // (plan index, question) → latest answer
  int rows = 0;
  // The file's columns: all of response_columns(), or all but the last (`sequence`) for a session
  // begun by a version without it; new rows keep the file's layout.
  size_t columns = 0;
  std::string dropped_tail;  // a partial last line (from a power cut), moved aside, not parsed
};

// Reads a session's responses and checks every row against the plan: the trial number, scene,
// method, σ and λ must be those the plan gives, or the session is refused (InputError), since
// resuming it would mix two different studies.
RecordedAnswers read_recorded_answers(const std::filesystem::path& csv, const runtime::Study& study,
                                      const std::vector<Trial>& plan);

class SessionRecorder {
 public:
  struct Identity {
    std::string subject;
    int session = 1;
    uint64_t seed = 1;  // the session seed the plan was made with
  };

  // New session: creates the three files (none may exist). Resume: they must exist, the sidecar's
  // plan must equal `plan`, and the recorded answers are read back.
  SessionRecorder(const runtime::Study& study, const std::vector<Trial>& plan, const Identity& who,
                  const std::filesystem::path& dir, bool resume);

  const RecordedAnswers& recorded() const { return recorded_; }
  const SessionFiles& files() const { return files_; }

  // Appends the answer's row and fsyncs it (and the trajectory, where the answer is logged too)
  // before returning. Practice answers go to the trajectory only.
  void record_answer(const Answer& answer, double time_s);
  // One trajectory line: the run time, an event name, a key name and the procedure's state.
  void log_event(double time_s, const std::string& event, const std::string& key,
                 const Procedure& procedure);
  void log_line(double time_s, const std::string& event, const std::string& key,
                const std::string& trial, const std::string& question,
                const std::string& lambda_index);

  // The current run, for the session to fill in; save() writes the sidecar.
  runtime::SessionRun& run() { return run_; }
  // The sidecar as save() writes it: the session's record, the earlier runs and this one.
  nlohmann::ordered_json sidecar() const;
  void save();

 private:
  void create(const std::filesystem::path& dir);  // a new session's files, refusing existing ones
  void open_existing();                           // a session to resume, checked against the plan
  void check_sidecar_is_this_sessions() const;
  void move_partial_line_aside();
  // The folder of the sequence an answer chose (the `sequence` column); empty for a still.
  std::string answered_sequence(int condition, int lambda_index) const;

  const runtime::Study& study_;
  const std::vector<Trial>& plan_;
  Identity who_;
  SessionFiles files_;
  AppendOnlyFile csv_, keys_;
  RecordedAnswers recorded_;
  nlohmann::ordered_json sidecar_;  // all but the current run
  runtime::SessionRun run_;
};

// The plan as stored in the sidecar (one compact object per trial), for the resume check.
nlohmann::ordered_json plan_to_json(const runtime::Study& study, const std::vector<Trial>& plan);

}  // namespace countershade::adjust
