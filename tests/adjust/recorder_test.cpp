// The session files: never overwritten, rows the analysis reads, resume checks and repairs.

#include "adjust/recorder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "analysis/responses.h"
#include "tiny_set.h"

namespace countershade::adjust {

// From the study runtime (src/runtime).
using runtime::load_study;
using runtime::RunEnd;
using runtime::Study;
namespace {

namespace fs = std::filesystem;

struct Fixture {
  testing::TempDir dir;
  Study study;
  std::vector<Trial> plan;
  SessionRecorder::Identity who{"P07", 2, 99};

  Fixture() : study(load_study(testing::make_tiny_set(dir), std::nullopt)) {
    PlanSettings s = study.config.plan;
    s.seed = who.seed;
    plan = plan_trials(study.conditions, s);
  }
  fs::path sessions() const { return dir / "sessions"; }
};

// Answers the first `count` questions of the plan with λ index (question + 1).
void answer(SessionRecorder& recorder, Procedure& p, int count) {
  p.press(Key::enter, 0);
  for (int i = 0; i < count; ++i) {
    while (p.lambda_index() < int(p.question()) + 1)
      p.press(Key::right, 1), p.release(Key::right, 1);
    while (p.lambda_index() > int(p.question()) + 1) p.press(Key::left, 1), p.release(Key::left, 1);
    auto a = p.press(Key::enter, 2 + i);
    ASSERT_TRUE(a);
    recorder.record_answer(*a, 2 + i);
  }
}

// A new session in which the first `count` questions are answered, then left without an end
// (as if the process was killed).
void record_session(const Fixture& f, int count) {
  SessionRecorder recorder(f.study, f.plan, f.who, f.sessions(), false);
  Procedure p(f.study.conditions, f.plan);
  answer(recorder, p, count);
}

TEST(AdjustRecorder, RowsCarryEveryColumnAndTheAnalysisReadsThem) {
  Fixture f;
  {
    SessionRecorder recorder(f.study, f.plan, f.who, f.sessions(), false);
    Procedure p(f.study.conditions, f.plan);
    answer(recorder, p, 5);
    recorder.save();
  }
  const auto files = session_files(f.sessions(), "P07", 2);
  EXPECT_EQ(files.csv.filename(), "P07_s02.csv");
  auto rows = analysis::read_responses(files.csv);
  ASSERT_EQ(rows.size(), 5u);
  for (size_t i = 0; i < rows.size(); ++i) {
    const Condition& c = f.study.conditions[size_t(f.plan[i / 3].condition)];
    EXPECT_EQ(rows[i].subject, "P07");
    EXPECT_EQ(rows[i].scene, c.scene);
    EXPECT_EQ(rows[i].method, "usm3d");
    EXPECT_DOUBLE_EQ(rows[i].sigma, c.sigma);
    EXPECT_EQ(int(rows[i].question), int(i % 3));
    EXPECT_DOUBLE_EQ(rows[i].lambda, 0.4 * double(i % 3 + 1));
    EXPECT_DOUBLE_EQ(rows[i].lambda_step, 0.4);
  }
  auto table = parse_csv(testing::read_file(files.csv), "csv");
  EXPECT_EQ(table.rows[0], response_columns());
  auto field = [&](size_t row, const std::string& name) {
    const auto& header = table.rows[0];
    return table.rows[row][size_t(std::find(header.begin(), header.end(), name) - header.begin())];
  };
  EXPECT_EQ(field(1, "trial"), "1");
  EXPECT_EQ(field(1, "stimulus_set"), f.study.manifest_sha256);
  EXPECT_EQ(field(1, "lambda_max"), format_value(f.study.lambda_max(f.plan[0].condition)));
  for (const auto& r : rows)
    EXPECT_DOUBLE_EQ(r.lambda_max, f.study.lambda_max(f.plan[0].condition));
  EXPECT_EQ(testing::count_lines(testing::read_file(files.keys)) > 5, true);
  auto sidecar = nlohmann::json::parse(testing::read_file(files.sidecar));
  EXPECT_EQ(sidecar["seed"], 99);
  EXPECT_EQ(sidecar["plan"].size(), f.plan.size());
  EXPECT_EQ(sidecar["runs"][0]["answers"], 5);
}

TEST(AdjustRecorder, AnExistingSessionIsNeverOverwritten) {
  Fixture f;
  { SessionRecorder recorder(f.study, f.plan, f.who, f.sessions(), false); }
  const auto files = session_files(f.sessions(), "P07", 2);
  const std::string before = testing::read_file(files.csv);
  std::string message = testing::input_error_of(
      [&] { SessionRecorder again(f.study, f.plan, f.who, f.sessions(), false); });
  EXPECT_NE(message.find("already exists"), std::string::npos) << message;
  EXPECT_EQ(testing::read_file(files.csv), before);
  message = testing::input_error_of([&] {
    SessionRecorder other(f.study, f.plan, {"P08", 1, 99}, f.sessions(), true);
  });
  EXPECT_NE(message.find("no session to resume"), std::string::npos) << message;
}

TEST(AdjustRecorder, ResumeReadsTheAnswersBackAndMarksTheKilledRun) {
  Fixture f;
  record_session(f, 4);
  SessionRecorder resumed(f.study, f.plan, f.who, f.sessions(), true);
  const auto& got = resumed.recorded();
  EXPECT_EQ(got.rows, 4);
  ASSERT_EQ(got.answered.size(), 4u);
  EXPECT_EQ(got.answered.at({1, 0}).lambda_index, 1);
  EXPECT_EQ(resumed.sidecar()["runs"][0]["end"], "interrupted");
  EXPECT_EQ(resumed.run().end, RunEnd::running);
  EXPECT_EQ(resumed.sidecar()["runs"][1]["end"], "running");
  EXPECT_EQ(resumed.run().answers_before, 4);
  Procedure p(f.study.conditions, f.plan);
  p.resume(got.answered);
  p.press(Key::enter, 0);
  EXPECT_EQ(p.trial_index(), 1);
  EXPECT_EQ(p.question(), Question::high);
}

// A session begun before responses had the `sequence` column (its last) goes on in that layout:
// its rows stay readable and the new rows match them.
TEST(AdjustRecorder, ASessionWithoutTheSequenceColumnResumesInItsOwnLayout) {
  Fixture f;
  record_session(f, 2);
  const auto files = session_files(f.sessions(), "P07", 2);
  std::string old;
  std::istringstream lines(testing::read_file(files.csv));
  for (std::string line; std::getline(lines, line);)
    old += line.substr(0, line.rfind(',')) + "\n";  // drop the last field
  testing::write_file(files.csv, old);
  {
    SessionRecorder resumed(f.study, f.plan, f.who, f.sessions(), true);
    EXPECT_EQ(resumed.recorded().rows, 2);
    Procedure p(f.study.conditions, f.plan);
    p.resume(resumed.recorded().answered);
    p.press(Key::enter, 0);
    while (p.lambda_index() < 3) p.press(Key::right, 1), p.release(Key::right, 1);
    auto a = p.press(Key::enter, 3);
    ASSERT_TRUE(a);
    resumed.record_answer(*a, 3);
  }
  const auto table = parse_csv(testing::read_file(files.csv), files.csv.string());
  ASSERT_EQ(table.rows.size(), 4u);
  for (const auto& row : table.rows) EXPECT_EQ(row.size(), response_columns().size() - 1);
  EXPECT_EQ(analysis::read_responses(files.csv).size(), 3u);
}

TEST(AdjustRecorder, APartialLastLineIsMovedAsideNotLost) {
  Fixture f;
  record_session(f, 2);
  const auto files = session_files(f.sessions(), "P07", 2);
  const std::string whole = testing::read_file(files.csv);
  testing::write_file(files.csv, whole + "P07,front,0.0");  // a write cut short by a power loss
  SessionRecorder resumed(f.study, f.plan, f.who, f.sessions(), true);
  EXPECT_EQ(resumed.recorded().rows, 2);
  EXPECT_EQ(resumed.recorded().dropped_tail, "P07,front,0.0");
  EXPECT_EQ(testing::read_file(files.csv), whole);
  ASSERT_EQ(resumed.sidecar()["repairs"].size(), 1u);
  fs::path aside = f.sessions() / resumed.sidecar()["repairs"][0]["file"].get<std::string>();
  EXPECT_EQ(testing::read_file(aside), "P07,front,0.0");
}

// A new session writes its sidecar before its answer files, so a kill in between leaves those
// missing (or, after a power cut, empty): the session resumes and records as one never stopped.
TEST(AdjustRecorder, ASessionKilledRightAfterItsSidecarResumes) {
  for (const bool empty_files : {false, true}) {
    Fixture f;
    { SessionRecorder recorder(f.study, f.plan, f.who, f.sessions(), false); }
    const auto files = session_files(f.sessions(), "P07", 2);
    const std::string header = testing::read_file(files.csv);
    const std::string keys_header = testing::read_file(files.keys);
    for (const fs::path& p : {files.csv, files.keys})
      empty_files ? void(testing::write_file(p, "")) : void(fs::remove(p));
    {
      SessionRecorder resumed(f.study, f.plan, f.who, f.sessions(), true);
      EXPECT_EQ(resumed.recorded().rows, 0);
      EXPECT_EQ(resumed.sidecar()["runs"][0]["end"], "interrupted");
      Procedure p(f.study.conditions, f.plan);
      answer(resumed, p, 2);
    }
    EXPECT_EQ(testing::read_file(files.keys).substr(0, keys_header.size()), keys_header);
    const std::string csv = testing::read_file(files.csv);
    EXPECT_EQ(csv.substr(0, header.size()), header) << "empty files: " << empty_files;
    EXPECT_EQ(analysis::read_responses(files.csv).size(), 2u);
  }
}

// What a kill cannot leave: answers whose sidecar is gone, or a sidecar that recorded answers in
// a file that is gone. Both are refused, and nothing is written.
TEST(AdjustRecorder, AnswersWithoutTheirSidecarOrTheReverseAreRefused) {
  Fixture f;
  {
    SessionRecorder recorder(f.study, f.plan, f.who, f.sessions(), false);
    Procedure p(f.study.conditions, f.plan);
    answer(recorder, p, 3);
    recorder.save();  // the sidecar records the three answers
  }
  const auto files = session_files(f.sessions(), "P07", 2);
  const std::string csv = testing::read_file(files.csv);
  const std::string sidecar = testing::read_file(files.sidecar);
  fs::remove(files.csv);
  std::string message = testing::input_error_of(
      [&] { SessionRecorder r(f.study, f.plan, f.who, f.sessions(), true); });
  EXPECT_NE(message.find("records 3 answers"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(files.csv));
  EXPECT_EQ(testing::read_file(files.sidecar), sidecar);

  testing::write_file(files.csv, csv);
  fs::remove(files.sidecar);
  message = testing::input_error_of(
      [&] { SessionRecorder r(f.study, f.plan, f.who, f.sessions(), true); });
  EXPECT_NE(message.find("cannot be checked and resumed"), std::string::npos) << message;
  message = testing::input_error_of(
      [&] { SessionRecorder r(f.study, f.plan, f.who, f.sessions(), false); });
  EXPECT_NE(message.find("already exists"), std::string::npos) << message;
  EXPECT_EQ(testing::read_file(files.csv), csv);
  EXPECT_FALSE(fs::exists(files.sidecar));
}

// A sidecar whose runs are not objects (edited by hand) is one line naming it.
TEST(AdjustRecorder, ASidecarWhoseRunsAreNotRunsIsRefusedInOneLine) {
  Fixture f;
  record_session(f, 1);
  const auto files = session_files(f.sessions(), "P07", 2);
  auto sidecar = nlohmann::ordered_json::parse(testing::read_file(files.sidecar));
  sidecar["runs"] = nlohmann::ordered_json::array({1, "two"});
  testing::write_file(files.sidecar, sidecar.dump());
  const std::string message = testing::input_error_of(
      [&] { SessionRecorder r(f.study, f.plan, f.who, f.sessions(), true); });
  EXPECT_NE(message.find("not a session sidecar"), std::string::npos) << message;
  EXPECT_EQ(testing::read_file(files.sidecar), sidecar.dump());
}

TEST(AdjustRecorder, ResumeRefusesRowsOrPlansFromAnotherStudy) {
  Fixture f;
  record_session(f, 1);
  const auto files = session_files(f.sessions(), "P07", 2);
  // Another seed gives another plan.
  std::string message = testing::input_error_of([&] {
    SessionRecorder r(f.study, f.plan, {"P07", 2, 100}, f.sessions(), true);
  });
  EXPECT_NE(message.find("plan"), std::string::npos) << message;
  // A row edited to another scene no longer matches its trial.
  std::string text = testing::read_file(files.csv);
  const std::string scene = f.study.conditions[size_t(f.plan[0].condition)].scene;
  const std::string other = scene == "front" ? "small" : "front";
  auto at = text.find("\nP07," + scene + ",");
  ASSERT_NE(at, std::string::npos);
  testing::write_file(files.csv, text.replace(at + 5, scene.size(), other));
  message = testing::input_error_of(
      [&] { SessionRecorder r(f.study, f.plan, f.who, f.sessions(), true); });
  EXPECT_NE(message.find("does not match trial 1"), std::string::npos) << message;
}

TEST(AdjustRecorder, TheAnalysisCountsOnlyTheLatestRevisionOfAnAnswer) {
  Fixture f;
  {
    SessionRecorder recorder(f.study, f.plan, f.who, f.sessions(), false);
    Procedure p(f.study.conditions, f.plan, {});
    p.press(Key::enter, 0);
    while (p.lambda_index() > 0) p.press(Key::left, 0), p.release(Key::left, 0);
    p.press(Key::right, 0), p.release(Key::right, 0);
    recorder.record_answer(*p.press(Key::enter, 1), 1);  // low = index 1
    p.press(Key::backspace, 2);
    p.press(Key::right, 2), p.release(Key::right, 2);
    recorder.record_answer(*p.press(Key::enter, 3), 3);  // low again = index 2, revision 1
  }
  const auto files = session_files(f.sessions(), "P07", 2);
  EXPECT_EQ(testing::count_lines(testing::read_file(files.csv)), 3);  // header + both rows kept
  auto rows = analysis::read_responses(files.csv);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_DOUBLE_EQ(rows[0].lambda, 0.8);
}

}  // namespace
}  // namespace countershade::adjust
