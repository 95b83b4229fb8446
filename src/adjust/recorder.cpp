#include "adjust/recorder.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/file_bytes.h"
#include "core/number_format.h"
#include "core/time.h"
#include "core/version.h"
#include "formats/responses.h"

namespace countershade::adjust {

// From the study runtime (src/runtime).
using runtime::Study;

namespace fs = std::filesystem;
using OrderedJson = nlohmann::ordered_json;

namespace {

constexpr int kSidecarFormatVersion = 1;

std::string two_digits(int session) {
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "%02d", session);
  return buffer;
}

}  // namespace

SessionFiles session_files(const fs::path& dir, const std::string& subject, int session) {
  const std::string stem = subject + "_s" + two_digits(session);
  return {dir / (stem + ".csv"), dir / (stem + ".json"), dir / (stem + ".keys.tsv")};
}

// ---------------------------------------------------------------------------------------------
// Reading a session back

namespace {

size_t column(const char* name) {
  const auto& cols = response_columns();
  return size_t(std::find(cols.begin(), cols.end(), name) - cols.begin());
}

// The session file's rows, its header checked (all columns, or all but the last `sequence` of an
// older version's file). A line without its newline can only come from a write cut short by a
// power loss (a killed process still completes its write): its bytes go to `dropped_tail`.
CsvTable read_session_table(const fs::path& csv, RecordedAnswers& out) {
  std::string text = read_file_bytes(csv);
  size_t end = text.rfind('\n');
  size_t keep = end == std::string::npos ? 0 : end + 1;
  if (keep < text.size()) {
    out.dropped_tail = text.substr(keep);
    text.resize(keep);
  }
  CsvTable table = parse_csv(text, csv.string());
  const auto& all = response_columns();
  const std::vector<std::string> without_sequence(all.begin(), all.end() - 1);
  if (table.rows.empty() || (table.rows[0] != all && table.rows[0] != without_sequence))
    throw_input_error(csv.string() + ": line 1",
                      "not a session file written by this app (unexpected header)");
  out.columns = table.rows[0].size();
  return table;
}

// One row checked against the plan (trial, scene, method, σ, λ) and recorded as an answer.
class RowReader {
 public:
  RowReader(const Study& study, const std::vector<Trial>& plan) : study_(study), plan_(plan) {
    for (size_t i = 0; i < plan.size(); ++i)
      if (!plan[i].practice) plan_index_of_number_[plan[i].number] = int(i);
  }

  void read(const std::vector<std::string>& row, const std::string& where,
            RecordedAnswers& out) const {
    if (row.size() != out.columns)
      throw_input_error(where, "expected " + std::to_string(out.columns) + " fields, found " +
                                   std::to_string(row.size()));
    const int number = integer(row, "trial", where);
    auto it = plan_index_of_number_.find(number);
    if (it == plan_index_of_number_.end())
      throw_input_error(where + " (trial)",
                        "trial " + std::to_string(number) + " is not in the plan");
    const Condition& c = study_.conditions[size_t(plan_[size_t(it->second)].condition)];
    const auto question = question_from_name(row[column("question")]);
    if (!question)
      throw_input_error(where + " (question)",
                        "unknown question '" + row[column("question")] + "'");
    const int lambda_index = integer(row, "lambda_index", where);
    if (row[column("scene")] != c.scene || row[column("method")] != c.method ||
        row[column("sigma")] != format_value(c.sigma) || lambda_index < 0 ||
        lambda_index >= c.grid_size ||
        row[column("lambda")] != format_value(study_.lambda(lambda_index)))
      throw_input_error(
          where,
          "the row does not match trial " + std::to_string(number) +
              " of this session's plan (was the stimulus set or the configuration changed?)");
    PastAnswer& past = out.answered[{it->second, int(*question)}];
    const int revision = integer(row, "revision", where);
    if (revision >= past.revision) past = PastAnswer{lambda_index, revision};
    ++out.rows;
  }

 private:
  static int integer(const std::vector<std::string>& row, const char* name,
                     const std::string& where) {
    const std::string& v = row[column(name)];
    try {
      size_t used = 0;
      int x = std::stoi(v, &used);
      if (used == v.size()) return x;
    } catch (const std::exception&) {
    }
    throw_input_error(where + " (" + name + ")", "'" + v + "' is not an integer");
  }

  const Study& study_;
  const std::vector<Trial>& plan_;
  std::map<int, int> plan_index_of_number_;
};

}  // namespace

RecordedAnswers read_recorded_answers(const fs::path& csv, const Study& study,
                                      const std::vector<Trial>& plan) {
  RecordedAnswers out;
  const CsvTable table = read_session_table(csv, out);
  const RowReader reader(study, plan);
  for (size_t r = 1; r < table.rows.size(); ++r)
    reader.read(table.rows[r], csv.string() + ": line " + std::to_string(table.lines[r]), out);
  return out;
}

// ---------------------------------------------------------------------------------------------
// SessionRecorder

OrderedJson plan_to_json(const Study& study, const std::vector<Trial>& plan) {
  OrderedJson out = OrderedJson::array();
  for (const auto& t : plan) {
    const Condition& c = study.conditions[size_t(t.condition)];
    out.push_back({{"trial", t.number},
                   {"practice", t.practice},
                   {"scene", c.scene},
                   {"method", c.method},
                   {"sigma", c.sigma},
                   {"repetition", t.repetition},
                   {"side", side_name(t.side)},
                   {"start_index", {t.start_index[0], t.start_index[1], t.start_index[2]}}});
  }
  return out;
}

SessionRecorder::SessionRecorder(const Study& study, const std::vector<Trial>& plan,
                                 const Identity& who, const fs::path& dir, bool resume)
    : study_(study), plan_(plan), who_(who), files_(session_files(dir, who.subject, who.session)) {
  run_.started_utc = utc_timestamp();
  run_.resumed = resume;
  if (resume)
    open_existing();
  else
    create(dir);
}

namespace {

std::string responses_header() {
  std::string header;
  for (size_t i = 0; i < response_columns().size(); ++i)
    header += (i ? "," : "") + response_columns()[i];
  return header + "\n";
}

const char* const kKeysHeader = "run\ttime_s\tevent\tkey\ttrial\tquestion\tlambda_index\n";

}  // namespace

// The sidecar is written before the answer files: a session killed at any moment after it began
// has its sidecar, and so can be resumed.
void SessionRecorder::create(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir, ec))
    throw_input_error(dir.string(), "cannot create the sessions folder");
  for (const auto& p : {files_.sidecar, files_.csv, files_.keys})
    if (fs::exists(p, ec))
      throw_input_error(
          p.string(),
          "already exists; a session is never overwritten (use --resume to continue it, "
          "or another --session number)");
  sidecar_ = {{"format_version", kSidecarFormatVersion},
              {"subject", who_.subject},
              {"session", who_.session},
              {"app_version", kVersion},
              {"manifest", fs::absolute(study_.manifest_path).lexically_normal().string()},
              {"stimulus_set", study_.manifest_sha256},
              {"set_name", study_.set_name},
              {"seed", who_.seed},
              {"config_source", study_.config_source},
              {"config", study_.config.to_json()},
              {"lambda_grid", {{"min", study_.lambda_min}, {"step", study_.lambda_step}}},
              {"plan", plan_to_json(study_, plan_)},
              {"runs", OrderedJson::array()}};
  save();
  csv_ = AppendOnlyFile::create(files_.csv, responses_header());
  keys_ = AppendOnlyFile::create(files_.keys, kKeysHeader);
}

void SessionRecorder::open_existing() {
  std::error_code ec;
  if (!fs::is_regular_file(files_.sidecar, ec))
    throw_input_error(files_.sidecar.string(),
                      fs::exists(files_.csv, ec)
                          ? "missing, so the answers beside it cannot be checked and resumed "
                            "(restore it, or start another --session number)"
                          : "no such file: there is no session to resume (start it without "
                            "--resume)");
  try {
    sidecar_ = OrderedJson::parse(read_file_bytes(files_.sidecar));
  } catch (const std::exception&) {
    throw_input_error(files_.sidecar.string(), "not valid JSON");
  }
  check_sidecar_is_this_sessions();
  // A kill right after the sidecar was written leaves the answer files missing or empty.
  csv_ = runtime::open_answers_to_resume(files_.csv, responses_header(), sidecar_["runs"]);
  keys_ = runtime::open_answers_to_resume(files_.keys, kKeysHeader, sidecar_["runs"]);
  recorded_ = read_recorded_answers(files_.csv, study_, plan_);
  runtime::mark_unended_runs_interrupted(sidecar_["runs"]);
  if (!recorded_.dropped_tail.empty()) move_partial_line_aside();
  run_.answers_before = recorded_.rows;
  save();
}

void SessionRecorder::check_sidecar_is_this_sessions() const {
  if (!sidecar_.is_object() || sidecar_.value("format_version", 0) != kSidecarFormatVersion ||
      !sidecar_.contains("runs") || !runtime::is_run_list(sidecar_["runs"]))
    throw_input_error(files_.sidecar.string(), "not a session sidecar written by this app");
  if (sidecar_.value("stimulus_set", std::string()) != study_.manifest_sha256)
    throw_input_error(
        files_.sidecar.string() + ": stimulus_set",
        "the session was recorded with another stimulus set (manifest sha256 differs)");
  if (sidecar_["plan"] != plan_to_json(study_, plan_) || sidecar_["seed"] != who_.seed)
    throw_input_error(
        files_.sidecar.string() + ": plan",
        "the trial plan differs from the one recorded (was the configuration or --seed changed?)");
}

void SessionRecorder::move_partial_line_aside() {
  const fs::path aside = files_.csv.string() + ".partial-" + utc_timestamp();
  write_text_atomically(aside, recorded_.dropped_tail);
  fs::resize_file(files_.csv, fs::file_size(files_.csv) - recorded_.dropped_tail.size());
  sidecar_["repairs"].push_back({{"at_utc", utc_timestamp()},
                                 {"what", "a partial last line of the responses was moved aside"},
                                 {"file", aside.filename().string()}});
}

std::string SessionRecorder::answered_sequence(int condition, int lambda_index) const {
  const int stimulus = study_.condition_images[size_t(condition)][size_t(1 + lambda_index)];
  return study_.stimuli[size_t(stimulus)].sequence;
}

void SessionRecorder::record_answer(const Answer& a, double time_s) {
  const Trial& t = plan_[size_t(a.trial_index)];
  log_line(time_s, a.revision ? "answer-revised" : "answer", "enter",
           t.practice ? "practice" : std::to_string(t.number), kQuestionNames[int(a.question)],
           std::to_string(a.lambda_index));
  if (t.practice) {
    keys_.sync();
    return;
  }
  const Condition& c = study_.conditions[size_t(t.condition)];
  char rt[32];
  std::snprintf(rt, sizeof rt, "%.1f", a.rt_s * 1000);
  std::vector<std::string> fields = {who_.subject,
                                     c.scene,
                                     format_value(c.sigma),
                                     kQuestionNames[int(a.question)],
                                     format_value(study_.lambda(a.lambda_index)),
                                     c.method,
                                     format_value(study_.lambda_step),
                                     std::to_string(a.lambda_index),
                                     format_value(study_.lambda_max(t.condition)),
                                     std::to_string(a.start_index),
                                     std::to_string(t.repetition),
                                     std::to_string(who_.session),
                                     std::to_string(t.number),
                                     side_name(t.side),
                                     std::to_string(a.n_keypresses),
                                     rt,
                                     std::to_string(a.revision),
                                     utc_timestamp(),
                                     study_.manifest_sha256,
                                     kVersion,
                                     answered_sequence(t.condition, a.lambda_index)};
  if (recorded_.columns) fields.resize(recorded_.columns);  // a resumed file keeps its layout
  csv_.append(csv_line(fields));
  csv_.sync();
  keys_.sync();
  ++run_.answers;
}

void SessionRecorder::log_event(double time_s, const std::string& event, const std::string& key,
                                const Procedure& p) {
  const bool in_trial =
      p.phase() == Procedure::Phase::question || p.phase() == Procedure::Phase::paused;
  const Trial& trial = p.trial();
  log_line(time_s, event, key,
           !in_trial        ? ""
           : trial.practice ? "practice"
                            : std::to_string(trial.number),
           in_trial ? kQuestionNames[int(p.question())] : "",
           in_trial ? std::to_string(p.lambda_index()) : "");
}

void SessionRecorder::log_line(double time_s, const std::string& event, const std::string& key,
                               const std::string& trial, const std::string& question,
                               const std::string& lambda_index) {
  char t[32];
  std::snprintf(t, sizeof t, "%.4f", time_s);
  // Tab-separated (no field holds a tab), so `analyze sessions/*.csv` never picks it up.
  keys_.append(std::to_string(sidecar_["runs"].size() + 1) + '\t' + t + '\t' + event + '\t' + key +
               '\t' + trial + '\t' + question + '\t' + lambda_index + '\n');
}

OrderedJson SessionRecorder::sidecar() const {
  OrderedJson out = sidecar_;
  out["runs"].push_back(run_.to_json());
  return out;
}

void SessionRecorder::save() { write_text_atomically(files_.sidecar, sidecar().dump(2) + "\n"); }

}  // namespace countershade::adjust
