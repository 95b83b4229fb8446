#include "forced_choice/choice_recorder.h"

#include <cmath>
#include <cstdio>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/file_bytes.h"
#include "core/json_reader.h"
#include "core/number_format.h"
#include "core/time.h"
#include "forced_choice/choice_row.h"
#include "formats/responses.h"

namespace countershade::forced_choice {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

ChoiceFiles choice_files(const fs::path& dir, const std::string& subject, int session) {
  char name[96];
  std::snprintf(name, sizeof name, "%s_s%02d.forced-choice", subject.c_str(), session);
  return {dir / (std::string(name) + ".csv"), dir / (std::string(name) + ".json")};
}

namespace {

// A partial last line (a power cut mid-write) is no answer: it is moved aside, and the trial is
// shown again.
void move_partial_line_aside(const fs::path& csv, json& sidecar) {
  const std::string text = read_file_bytes(csv);
  const size_t end = text.find_last_of('\n');
  const std::string tail = end == std::string::npos ? text : text.substr(end + 1);
  if (tail.empty()) return;
  const fs::path aside = csv.string() + ".partial-" + utc_timestamp();
  write_text_atomically(aside, tail);
  fs::resize_file(csv, text.size() - tail.size());
  sidecar["repairs"].push_back({{"at_utc", utc_timestamp()},
                                {"what", "a partial last line of the trials was moved aside"},
                                {"file", aside.filename().string()}});
}

}  // namespace

ChoiceRecorder::ChoiceRecorder(const runtime::Study& study, const ChoiceConfig& config,
                               const Identity& who, const fs::path& dir, bool resume,
                               ChoiceRun& run)
    : study_(study),
      config_(config),
      who_(who),
      files_(choice_files(dir, who.subject, who.session)) {
  run_.started_utc = utc_timestamp();
  run_.resumed = resume;
  if (resume)
    resume_session(run);
  else
    begin_session(run);
}

// The sidecar is written before the trials file: a session killed at any moment after it began
// has its sidecar, and so can be resumed.
void ChoiceRecorder::begin_session(const ChoiceRun& run) {
  for (const fs::path& p : {files_.sidecar, files_.csv})
    if (fs::exists(p))
      throw_input_error(p.string(), "exists already (use --resume to continue it)");
  sidecar_ = {
      {"format", "countershade-forced-choice-session"},
      {"subject", who_.subject},
      {"session", who_.session},
      {"seed", who_.seed},
      {"set", {{"manifest", study_.manifest_path.string()}, {"sha256", study_.manifest_sha256}}},
      {"config", config_.to_json()},
      {"runs", json::array()}};
  save(run);
  csv_ = AppendOnlyFile::create(files_.csv, csv_line(choice_columns()));
}

void ChoiceRecorder::resume_session(ChoiceRun& run) {
  if (!fs::exists(files_.sidecar))
    throw_input_error(files_.sidecar.string(),
                      fs::exists(files_.csv)
                          ? "missing, so its trials cannot be checked and resumed (restore it, "
                            "or start another --session)"
                          : "no session to resume (start it without --resume)");
  try {
    sidecar_ = json::parse(read_file_bytes(files_.sidecar));
  } catch (const json::parse_error&) {
    throw_input_error(files_.sidecar.string(), "not valid JSON");
  }
  if (!sidecar_.is_object() || !sidecar_["set"].is_object() ||
      !runtime::is_run_list(sidecar_["runs"]))
    throw_input_error(files_.sidecar.string(), "not a forced-choice session's sidecar");
  if (sidecar_.value("seed", uint64_t(0)) != who_.seed || sidecar_["config"] != config_.to_json() ||
      sidecar_["set"]["sha256"] != study_.manifest_sha256)
    throw_input_error(files_.sidecar.string(),
                      "this session was begun with another set, seed or configuration");
  runtime::mark_unended_runs_interrupted(sidecar_["runs"]);
  if (fs::exists(files_.csv)) move_partial_line_aside(files_.csv, sidecar_);
  csv_ = runtime::open_answers_to_resume(files_.csv, csv_line(choice_columns()), sidecar_["runs"]);
  replay(run);
}

void ChoiceRecorder::replay(ChoiceRun& run) {
  const std::string file = files_.csv.string();
  const CsvTable table = parse_csv(read_file_bytes(files_.csv), file);
  if (table.rows.empty() || table.rows.front() != choice_columns())
    throw_input_error(file, "not a forced-choice session (its header differs)");
  const std::vector<std::vector<std::string>> rows(table.rows.begin() + 1, table.rows.end());
  replay_choice_rows(run, rows, study_, config_.n_afc,
                     [&](size_t r) { return file + ":" + std::to_string(table.lines[r + 1]); });
  rows_ = int(rows.size());
  run_.answers_before = rows_;
}

void ChoiceRecorder::record(const ChoiceTrial& t, int response, bool correct, double rt_s) {
  csv_.append(
      csv_line(choice_row(study_, config_, {who_.subject, who_.session, study_.manifest_sha256}, t,
                          response, correct, rt_s, utc_timestamp())));
  csv_.sync();
  ++rows_;
  ++run_.answers;
}

void ChoiceRecorder::save(const ChoiceRun& run) {
  json out = sidecar_;
  out["runs"].push_back(run_.to_json());
  out["procedures"] = json::array();
  for (int c : run.conditions()) {
    const auto& condition = study_.conditions[size_t(c)];
    out["procedures"].push_back({{"scene", condition.scene},
                                 {"method", condition.method},
                                 {"sigma", condition.sigma},
                                 {"state", run.procedure_state(c)}});
  }
  write_text_atomically(files_.sidecar, out.dump(2) + "\n");
}

}  // namespace countershade::forced_choice
