// The rows both apps write, held against fixtures: sessions of `adjust` and `choose` with the
// simulated observers on the frame clock (the adjustment procedure, constant stimuli, a staircase
// and QUEST; 8- and 16-bit sets) and sessions resumed after SIGKILL. The fixtures in
// tests/study/fixtures/ were recorded from the apps as they were before the study runtime
// (see the README there), so a restructure of the runtime that changes a row fails here.
//
// To record them from another binary, set COUNTERSHADE_SESSION_BINARY to it and
// COUNTERSHADE_RECORD_FIXTURES to the folder to write, and run --gtest_filter='SessionRows.*'.

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>

#include "../adjust/app_runner.h"
#include "../adjust/tiny_set.h"
#include "formats/responses.h"

namespace countershade::testing {
namespace {

namespace fs = std::filesystem;

std::string binary() {
  const char* other = std::getenv("COUNTERSHADE_SESSION_BINARY");
  return other ? other : COUNTERSHADE_BINARY;
}

// The columns that depend on the clock or on the build: times, the set's hash and the version.
bool varies_between_runs(const std::string& column) {
  static const std::set<std::string> columns = {"rt_ms",        "timestamp_utc", "time_utc",
                                                "stimulus_set", "set_sha256",    "app_version"};
  return columns.count(column) > 0;
}

// The responses file with the varying columns replaced by '*', one line per row.
std::string normalised_rows(const fs::path& csv) {
  const CsvTable table = parse_csv(read_file(csv), csv.string());
  std::string out;
  for (const auto& row : table.rows) {
    for (size_t c = 0; c < row.size(); ++c) {
      const bool varies = &row != &table.rows[0] && varies_between_runs(table.rows[0][c]);
      out += (c ? "," : "") + (varies ? std::string("*") : row[c]);
    }
    out += "\n";
  }
  return out;
}

// Compares the session's rows with the fixture `name`, or records them when asked to.
void expect_fixture_rows(const fs::path& csv, const std::string& name) {
  const std::string rows = normalised_rows(csv);
  if (const char* record = std::getenv("COUNTERSHADE_RECORD_FIXTURES")) {
    write_file(fs::path(record) / (name + ".csv"), rows);
    return;
  }
  EXPECT_EQ(rows, read_file(source_dir() / "tests/study/fixtures" / (name + ".csv"))) << name;
}

std::vector<std::string> app_args(const std::string& app, const fs::path& manifest,
                                  const fs::path& sessions, std::vector<std::string> extra) {
  std::vector<std::string> args = {binary(), app,          manifest.string(), "--subject",
                                   "P01",    "--sessions", sessions.string()};
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

void run_to_end(const std::vector<std::string>& args, const fs::path& log) {
  XvfbServer x;
  Child app(args, x.display(), log.string());
  ASSERT_EQ(app.wait(300), 0) << read_file(log);
}

size_t lines_in(const fs::path& file) {
  return fs::exists(file) ? size_t(count_lines(read_file(file))) : 0;
}

// Kills the session with SIGKILL once its file holds `rows` rows (header included), then resumes
// it to the end.
void kill_then_resume(const std::vector<std::string>& args, const fs::path& csv, size_t rows,
                      const fs::path& log) {
  XvfbServer x;
  {
    Child app(args, x.display(), log.string());
    for (int i = 0; i < 60000 && app.running() && lines_in(csv) < rows; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    ASSERT_TRUE(app.running()) << "the session ended before the kill: " << read_file(log);
    app.kill_hard();
  }
  std::vector<std::string> resumed = args;
  resumed.push_back("--resume");
  Child app(resumed, x.display(), log.string());
  ASSERT_EQ(app.wait(300), 0) << read_file(log);
}

// SIGTERM once the file holds `rows` rows: the app saves and exits 0 with the run recorded as
// terminated; a resume then ends the session.
void terminate_then_resume(const std::vector<std::string>& args, const fs::path& csv,
                           const fs::path& sidecar, size_t rows, const fs::path& log) {
  XvfbServer x;
  {
    Child app(args, x.display(), log.string());
    for (int i = 0; i < 60000 && app.running() && lines_in(csv) < rows; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    ASSERT_TRUE(app.running()) << "the session ended before the signal: " << read_file(log);
    app.send(SIGTERM);
    ASSERT_EQ(app.wait(60), 0) << read_file(log);
  }
  const auto runs = nlohmann::json::parse(read_file(sidecar))["runs"];
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_EQ(runs[0]["end"], "terminated") << runs;
  std::vector<std::string> resumed = args;
  resumed.push_back("--resume");
  Child app(resumed, x.display(), log.string());
  ASSERT_EQ(app.wait(300), 0) << read_file(log);
}

const std::string kQuest =
    R"({"type": "quest", "tGuess": -0.3, "tGuessSd": 1, "pThreshold": 0.82, "beta": 3.5,
        "delta": 0.01, "gamma": 0.5, "grain": 0.01, "range": 4, "nTrials": 10})";
const std::string kStaircase =
    R"({"type": "staircase", "startVal": 1.0, "stepSizes": [0.4, 0.2, 0.1], "nUp": 1, "nDown": 2,
        "stepType": "lin", "minVal": 0.1, "maxVal": 2.0, "nTrials": 12, "nReversals": 2})";
const std::string kConstant =
    R"({"type": "constant", "lambdas": [0.2, 0.6, 1.0, 1.4], "repetitions": 3})";

// A two-scene set over λ 0 … 2 in steps of 0.1 with the given forced-choice block and output.
fs::path choice_set(const TempDir& dir, const std::string& block, const std::string& more = "") {
  return make_tiny_set(dir, "", 96, 72, 0.1, more + "\"forced_choice\": " + block + ",");
}

const std::string kTwoConditions =
    R"("conditions": [{"scene": "front", "method": "usm3d", "sigma": 0.03},
                      {"scene": "small", "method": "usm3d", "sigma": 0.08}])";

void choose_rows(const std::string& block, const std::string& fixture, const std::string& more,
                 const std::string& observer = "weibull:0.4,3,11") {
  TempDir dir;
  const auto manifest = choice_set(dir, block, more);
  run_to_end(app_args("choose", manifest, dir / "s", {"--observer", observer, "--frame-clock"}),
             dir / "log.txt");
  expect_fixture_rows(dir / "s/P01_s01.forced-choice.csv", fixture);
}

TEST(SessionRows, AdjustmentOnAnEightBitSet) {
  TempDir dir;
  const auto manifest = make_tiny_set(dir, R"({"repetitions": 2, "practice_trials": 1})");
  run_to_end(
      app_args("adjust", manifest, dir / "s", {"--observer", "simulated:3", "--frame-clock"}),
      dir / "log.txt");
  expect_fixture_rows(dir / "s/P01_s01.csv", "adjust-8bit");
}

TEST(SessionRows, AdjustmentOnASixteenBitSetThroughTheDither) {
  TempDir dir;
  const auto manifest = make_tiny_set(dir, "", 96, 72, 0.4, R"("output": {"bits": 16},)");
  run_to_end(app_args("adjust", manifest, dir / "s",
                      {"--observer", "simulated:5", "--frame-clock", "--output-path", "dither"}),
             dir / "log.txt");
  expect_fixture_rows(dir / "s/P01_s01.csv", "adjust-16bit");
}

TEST(SessionRows, AdjustmentResumedAfterSigkill) {
  TempDir dir;
  const auto manifest = make_tiny_set(dir, R"({"repetitions": 3})");
  kill_then_resume(app_args("adjust", manifest, dir / "s", {"--observer", "simulated:7"}),
                   dir / "s/P01_s01.csv", 9, dir / "log.txt");
  expect_fixture_rows(dir / "s/P01_s01.csv", "adjust-resumed");
}

TEST(SessionRows, ConstantStimuli) {
  choose_rows("{" + kTwoConditions + R"(, "procedure": )" + kConstant + "}", "choose-constant", "");
}

TEST(SessionRows, StaircaseWithThreeAlternatives) {
  choose_rows("{" + kTwoConditions + R"(, "n_afc": 3, "procedure": )" + kStaircase + "}",
              "choose-staircase", "");
}

TEST(SessionRows, QuestTemporalOnASixteenBitSet) {
  choose_rows("{" + kTwoConditions + R"(, "layout": "temporal", "interval_frames": 2,
              "blank_frames": 1, "practice_trials": 2, "procedure": )" +
                  kQuest + "}",
              "choose-quest-16bit", R"("output": {"bits": 16},)");
}

TEST(SessionRows, QuestResumedAfterSigkill) {
  TempDir dir;
  const auto manifest = choice_set(dir, "{" + kTwoConditions + R"(, "procedure": )" + kQuest + "}");
  kill_then_resume(app_args("choose", manifest, dir / "s", {"--observer", "weibull:0.4,3,11"}),
                   dir / "s/P01_s01.forced-choice.csv", 8, dir / "log.txt");
  expect_fixture_rows(dir / "s/P01_s01.forced-choice.csv", "choose-quest-resumed");
}

// Both apps end cleanly on SIGTERM and resume to the same rows as after a SIGKILL.
TEST(SessionRows, AdjustmentTerminatedBySigtermAndResumed) {
  TempDir dir;
  const auto manifest = make_tiny_set(dir, R"({"repetitions": 3})");
  terminate_then_resume(app_args("adjust", manifest, dir / "s", {"--observer", "simulated:7"}),
                        dir / "s/P01_s01.csv", dir / "s/P01_s01.json", 9, dir / "log.txt");
  expect_fixture_rows(dir / "s/P01_s01.csv", "adjust-resumed");
}

TEST(SessionRows, QuestTerminatedBySigtermAndResumed) {
  TempDir dir;
  const auto manifest = choice_set(dir, "{" + kTwoConditions + R"(, "procedure": )" + kQuest + "}");
  terminate_then_resume(app_args("choose", manifest, dir / "s", {"--observer", "weibull:0.4,3,11"}),
                        dir / "s/P01_s01.forced-choice.csv", dir / "s/P01_s01.forced-choice.json",
                        8, dir / "log.txt");
  expect_fixture_rows(dir / "s/P01_s01.forced-choice.csv", "choose-quest-resumed");
}

}  // namespace
}  // namespace countershade::testing
