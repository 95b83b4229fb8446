// The adjustment app end to end: the real binary in a real window on a private Xvfb server,
// driven by key scripts, the simulated observer, xdotool, and SIGKILL.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <sstream>

#include "adjust/recorder.h"
#include "adjust/simulated_observer.h"
#include "analysis/responses.h"
#include "app_runner.h"
#include "core/image.h"
#include "runtime/key_script.h"
#include "runtime/study.h"
#include "tiny_set.h"
#include "x_display.h"

namespace countershade::adjust {

// From the study runtime (src/runtime).
using runtime::load_study;
using runtime::Study;
namespace {

// The position of a column in the responses CSV the app writes.
size_t column(const std::string& name) {
  const auto& columns = response_columns();
  return size_t(std::find(columns.begin(), columns.end(), name) - columns.begin());
}

namespace fs = std::filesystem;
using nlohmann::json;
using testing::adjust_args;
using testing::run_app;

// Waits until the app's window exists and its stimuli are loaded (up to 120 s: only a hang should
// stop it): key presses during loading are ignored on purpose, so a test must not send them
// earlier.
bool wait_until_ready(const fs::path& sidecar, const std::string& xdotool) {
  for (int i = 0; i < 1200; ++i) {
    if (fs::exists(sidecar)) {
      auto runs = json::parse(testing::read_file(sidecar))["runs"];
      if (!runs.empty() && runs.back().contains("preload") &&
          std::system((xdotool + "search --name 'countershade adjust' >/dev/null 2>&1").c_str()) ==
              0)
        return true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return false;
}

TEST(AdjustGui, AScriptedSessionWritesExactlyTheExpectedRows) {
  testing::TempDir dir;
  auto manifest = testing::make_tiny_set(dir, R"({"repetitions": 2, "start": "zero"})");
  // Every trial: low at index 1, high at 3, best at 2. In trial 1 the observer goes back from
  // high and changes low to 2 (a second row with revision 1).
  std::string script = "300 enter\n";
  for (int trial = 1; trial <= 8; ++trial) {
    script += "15 right\n15 enter\n";
    if (trial == 1) script += "15 backspace\n15 right\n15 enter\n";
    script += "15 right\n15 right\n15 right\n15 enter\n15 right\n15 right\n15 enter\n";
  }
  testing::write_file(dir / "keys.txt", script);
  testing::XvfbServer x;
  ASSERT_EQ(run_app(x,
                    adjust_args(manifest, dir / "sessions", "P01",
                                {"--script", (dir / "keys.txt").string(), "--frame-clock"}),
                    dir / "log.txt"),
            0)
      << testing::read_file(dir / "log.txt");
  EXPECT_NE(testing::read_file(dir / "log.txt").find("completed; 24 of 24 answers"),
            std::string::npos)
      << testing::read_file(dir / "log.txt");

  const fs::path csv = dir / "sessions/P01_s01.csv";
  EXPECT_EQ(testing::count_lines(testing::read_file(csv)), 1 + 24 + 1);
  auto table = parse_csv(testing::read_file(csv), csv.string());
  auto rows = analysis::read_responses(csv);
  ASSERT_EQ(rows.size(), 24u);
  Study study = load_study(manifest, std::nullopt);
  std::map<std::string, int> per_condition;
  std::map<int, std::set<std::string>> questions_of_trial;
  for (size_t r = 1; r < table.rows.size(); ++r) {
    const auto& row = table.rows[r];
    const int trial = std::stoi(row[column("trial")]),
              revision = std::stoi(row[column("revision")]);
    const std::string question = row[3];
    int expected = question == "low" ? 1 : question == "high" ? 3 : 2;
    if (trial == 1 && question == "low" && revision == 1) expected = 2;
    EXPECT_EQ(std::stoi(row[7]), expected) << "trial " << trial << " " << question;
    EXPECT_EQ(row[4], format_value(study.lambda(expected)));
    EXPECT_EQ(row[column("start_index")], "0");
    if (revision == 0) ++per_condition[row[1] + "/" + row[2] + "/rep" + row[column("repetition")]];
    questions_of_trial[trial].insert(question);
  }
  EXPECT_EQ(per_condition.size(), 8u);  // 4 conditions × 2 repetitions
  for (const auto& [key, n] : per_condition) EXPECT_EQ(n, 3) << key;
  for (int t = 1; t <= 8; ++t) EXPECT_EQ(questions_of_trial[t].size(), 3u);

  auto sidecar = json::parse(testing::read_file(dir / "sessions/P01_s01.json"));
  const auto& run = sidecar["runs"][0];
  EXPECT_EQ(run["end"], "completed");
  EXPECT_EQ(run["answers"], 25);
  EXPECT_EQ(run["preload"]["images"], 26);  // 2 references + 4 conditions × 6 grid images
  EXPECT_NE(run["display"]["gl_renderer"].get<std::string>(), "");
  EXPECT_GT(run["frames"]["all"]["count"].get<int>(), 10);
  // Every press reaches the screen with the next frame: 1 + 8 × 9 + 3 presses in the script. (The
  // time this takes is measured by bench/adjust/measure; the frame clock makes the run independent
  // of the machine's load.)
  EXPECT_EQ(run["frames"]["pacing"], "frame-clock");
  EXPECT_EQ(run["frames"]["key_to_frame"]["count"], 1 + 8 * 9 + 3);
  EXPECT_EQ(run["frames"]["key_to_frame_frames_max"], 1);
  const std::string keys = testing::read_file(dir / "sessions/P01_s01.keys.tsv");
  EXPECT_NE(keys.find("answer-revised"), std::string::npos);
}

TEST(AdjustGui, TheScreenshotShowsBothStimuliPixelExactOnAUniformSurround) {
  testing::TempDir dir;
  auto manifest = testing::make_tiny_set(dir);
  testing::write_file(dir / "keys.txt",
                      "300 enter\n40 right\n40 right\n100 screenshot\n40 close\n");
  testing::XvfbServer x;
  ASSERT_EQ(run_app(x,
                    adjust_args(manifest, dir / "sessions", "P02",
                                {"--script", (dir / "keys.txt").string(), "--screenshot",
                                 (dir / "shot.png").string()}),
                    dir / "log.txt"),
            0)
      << testing::read_file(dir / "log.txt");
  auto info = json::parse(testing::read_file(dir / "shot.png.json"));
  Image shot = read_image(dir / "shot.png");
  ASSERT_EQ(shot.channels, 3);
  EXPECT_GE(info["lambda_index"].get<int>(), 2);
  std::set<std::string> shown;
  for (const char* side : {"left", "right"}) {
    const auto& r = info[side];
    Image stimulus = read_image(dir / "set" / r["file"].get<std::string>());
    ASSERT_EQ(stimulus.width, r["width"].get<int>());
    ASSERT_EQ(stimulus.height, r["height"].get<int>());
    const int x0 = r["x"], y0 = r["y"];
    long differing = 0;
    for (int y = 0; y < stimulus.height; ++y)
      for (int x = 0; x < stimulus.width; ++x)
        for (int c = 0; c < 3; ++c)
          differing += std::lround(stimulus.at(x, y, c) * 255) !=
                       std::lround(shot.at(x0 + x, y0 + y, c) * 255);
    EXPECT_EQ(differing, 0) << side << ": " << r["file"];
    shown.insert(r["file"].get<std::string>());
  }
  // One side is the reference, the other the enhanced image at the adjusted λ.
  const std::string scene = (*shown.begin()).substr(0, (*shown.begin()).find('/'));
  EXPECT_TRUE(shown.count(scene + "/reference.png"));
  EXPECT_EQ(shown.size(), 2u);
  // The surround is the configured uniform grey, also between and around the stimuli.
  const int gap_x = info["left"]["x"].get<int>() + info["left"]["width"].get<int>() + 10;
  for (auto [x, y] : {std::pair{0, 0},
                      {shot.width - 1, shot.height - 1},
                      {gap_x, info["left"]["y"].get<int>() + 5}})
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(std::lround(shot.at(x, y, c) * 255), 128) << x << "," << y;
}

// Every answer exactly once, each the simulated observer's answer, the file parses cleanly, and the
// sidecar records every kill. Returns the rows of the responses file.
std::vector<std::vector<std::string>> check_every_answer_once(const fs::path& manifest,
                                                              const fs::path& dir, int answers,
                                                              int kills) {
  const fs::path sessions = dir / "sessions";
  const fs::path sidecar = sessions / "P03_s01.json";
  Study study = load_study(manifest, std::nullopt);
  SimulatedObserver observer(7, study);
  const fs::path csv = sessions / "P03_s01.csv";
  auto table = parse_csv(testing::read_file(csv), csv.string());
  EXPECT_EQ(table.rows.size(), 1u + size_t(answers));
  EXPECT_EQ(analysis::read_responses(csv).size(), size_t(answers));
  std::set<std::pair<int, std::string>> seen;
  auto sidecar_json = json::parse(testing::read_file(sidecar));
  for (size_t r = 1; r < table.rows.size(); ++r) {
    const auto& row = table.rows[r];
    const int trial = std::stoi(row[column("trial")]);
    EXPECT_TRUE(seen.insert({trial, row[3]}).second)
        << "trial " << trial << " " << row[3] << " twice";
    const auto& planned = sidecar_json["plan"][size_t(trial - 1)];
    int condition = -1;
    for (size_t c = 0; c < study.conditions.size(); ++c)
      if (study.conditions[c].scene == planned["scene"] &&
          study.conditions[c].sigma == planned["sigma"].get<double>())
        condition = int(c);
    EXPECT_GE(condition, 0);
    Question q = row[3] == "low"    ? Question::low
                 : row[3] == "high" ? Question::high
                                    : Question::best;
    EXPECT_EQ(std::stoi(row[7]), observer.answer_index(condition, planned["repetition"], q))
        << "trial " << trial;
  }
  EXPECT_EQ(seen.size(), size_t(answers));
  // The sidecar records every interruption.
  int interrupted = 0;
  for (const auto& run : sidecar_json["runs"]) interrupted += run["end"] == "interrupted";
  EXPECT_EQ(interrupted, kills);
  EXPECT_EQ(sidecar_json["runs"].back()["end"], "completed");
  return table.rows;
}

// Runs the simulated observer's session of `manifest`, killing it `max_kills` times at random
// moments and resuming, until it completes with all `answers`; then checks that every answer is
// there exactly once and is the observer's. Returns the rows of the responses file.
std::vector<std::vector<std::string>> kill_and_resume(const fs::path& manifest, const fs::path& dir,
                                                      int answers, int max_kills) {
  const fs::path sessions = dir / "sessions";
  const fs::path sidecar = sessions / "P03_s01.json";
  testing::XvfbServer x;
  std::mt19937 random(2024);
  std::uniform_real_distribution<double> kill_after(0.0, 0.7);
  auto runs_recorded = [&] {
    return fs::exists(sidecar) ? json::parse(testing::read_file(sidecar))["runs"].size()
                               : size_t(0);
  };
  const std::string done =
      "completed; " + std::to_string(answers) + " of " + std::to_string(answers);
  int kills = 0, launches = 0;
  bool complete = false;
  while (!complete && launches < 60) {
    std::vector<std::string> extra = {"--observer", "simulated:7"};
    if (fs::exists(sidecar)) extra.push_back("--resume");
    const size_t runs_before = runs_recorded();
    testing::Child app(adjust_args(manifest, sessions, "P03", extra), x.display(),
                       (dir / "log.txt").string());
    ++launches;
    if (kills < max_kills) {
      // Kill at a random point after the run has registered itself (so the sidecar can know of it):
      // during preloading, between answers, or in the middle of writing one.
      for (int i = 0; i < 1000 && runs_recorded() == runs_before && app.running(); ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      int status = app.wait(kill_after(random));
      if (status == -1) {
        app.kill_hard();
        ++kills;
        continue;
      }
      EXPECT_EQ(status, 0) << testing::read_file(dir / "log.txt");
    } else {
      EXPECT_EQ(app.wait(300), 0) << testing::read_file(dir / "log.txt");
    }
    complete = testing::read_file(dir / "log.txt").find(done) != std::string::npos;
  }
  EXPECT_TRUE(complete) << testing::read_file(dir / "log.txt");
  EXPECT_GE(kills, max_kills - 2);
  return check_every_answer_once(manifest, dir, answers, kills);
}

// On a 16-bit set (textures, the 10-bit check and the dither add nothing to what a kill can lose;
// the 8-bit path is killed in the sequence test below).
TEST(AdjustGui, KilledSessionsResumeWithEveryAnswerExactlyOnce) {
  testing::TempDir dir;
  const auto manifest = testing::make_tiny_set(dir, R"({"repetitions": 8})", 96, 72, 0.4,
                                               R"("output": {"bits": 16},)");
  kill_and_resume(manifest, dir.path(), 96, 12);
  const auto runs = json::parse(testing::read_file(dir / "sessions" / "P03_s01.json"))["runs"];
  EXPECT_EQ(runs.back()["display"]["output"]["stimulus_bits"], 16);
}

// A set of sequences: the rows name the sequence each answer chose, and a killed session still
// loses nothing.
TEST(AdjustGui, SequenceSessionsRecordTheChosenSequenceAndSurviveKills) {
  testing::TempDir dir;
  const auto rows =
      kill_and_resume(testing::make_sequence_set(dir, R"({"repetitions": 16})"), dir.path(), 48, 6);
  for (size_t r = 1; r < rows.size(); ++r)
    EXPECT_EQ(rows[r][column("sequence")],
              "orbit/usm2d/sigma-2/lambda-" + rows[r][column("lambda_index")])
        << r;
}

// The left and right files of a screenshot's sidecar, checked pixel for pixel against the shot.
std::pair<std::string, std::string> shown_files(const fs::path& shot, const fs::path& set) {
  const auto info = json::parse(testing::read_file(shot.string() + ".json"));
  const Image screen = read_image(shot);
  for (const char* side : {"left", "right"}) {
    const auto& r = info[side];
    const Image stimulus = read_image(set / r["file"].get<std::string>());
    long differing = 0;
    for (int y = 0; y < stimulus.height; ++y)
      for (int x = 0; x < stimulus.width; ++x)
        for (int c = 0; c < 3; ++c)
          differing +=
              std::lround(stimulus.at(x, y, c) * 255) !=
              std::lround(screen.at(r["x"].get<int>() + x, r["y"].get<int>() + y, c) * 255);
    EXPECT_EQ(differing, 0) << shot << " " << side << ": " << r["file"];
  }
  return {info["left"]["file"], info["right"]["file"]};
}

// Plays the sequence set for about 10 s with three screenshots (5 s in, 260 ms later, and after a
// λ step) and returns the run's record from the sidecar.
json play_for_ten_seconds(const fs::path& manifest, const fs::path& dir,
                          const std::string& subject) {
  testing::write_file(dir / "keys.txt",
                      "300 enter\n5000 screenshot\n260 screenshot\n100 right\n200 screenshot\n"
                      "4400 close\n");
  testing::XvfbServer x;
  EXPECT_EQ(run_app(x,
                    adjust_args(manifest, dir / "sessions", subject,
                                {"--script", (dir / "keys.txt").string(), "--screenshot",
                                 (dir / "shot.png").string(), "--frame-clock"}),
                    dir / "log.txt"),
            0)
      << testing::read_file(dir / "log.txt");
  return json::parse(testing::read_file(dir / "sessions" / (subject + "_s01.json")))["runs"][0];
}

// Two 512×384 sequences side by side for 10 s of the frame clock: both sides always show the same
// frame, the frames advance, and a λ step keeps playing. Whether a real display keeps up (no
// dropped frame at 60 Hz) is measured by bench/adjust/measure, not here: it depends on the load.
TEST(AdjustPlayback, TwoSequencesPlayInStepAndKeepPlayingAcrossALambdaStep) {
  testing::TempDir dir;
  const auto manifest = testing::make_sequence_set(dir, R"({"start": "zero"})", 512, 384);
  const json run = play_for_ten_seconds(manifest, dir.path(), "P09");
  auto frame_of = [](const std::string& file) { return fs::path(file).filename().string(); };
  std::vector<std::pair<std::string, std::string>> shots;
  for (const char* name : {"shot.png", "shot-2.png", "shot-3.png"})
    shots.push_back(shown_files(dir / name, dir / "set"));
  for (const auto& [left, right] : shots)
    EXPECT_EQ(frame_of(left), frame_of(right)) << left << " | " << right;
  EXPECT_NE(frame_of(shots[0].first), frame_of(shots[1].first));  // 260 ms apart at 4 fps
  const std::string after_step =
      shots[2].first.find("reference") == std::string::npos ? shots[2].first : shots[2].second;
  EXPECT_NE(after_step.find("lambda-1/"), std::string::npos) << after_step;

  EXPECT_EQ(run["preload"]["images"], 3 * 4);
  const auto& frames = run["frames"];
  EXPECT_EQ(frames["pacing"], "frame-clock");
  // 10.26 s of script at 60 frames per second, less the 20 frames that calibrate pacing and the 3
  // screenshots (neither is timed).
  EXPECT_NEAR(frames["all"]["count"].get<int>(), 10.26 * 60 - 23, 2);
}

TEST(AdjustGui, SimulatedObserverSessionsFeedTheAnalysis) {
  testing::TempDir dir;
  auto manifest = testing::make_tiny_set(dir);
  testing::XvfbServer x;
  std::string csvs;
  for (int subject = 1; subject <= 5; ++subject) {
    const std::string id = "S" + std::to_string(subject);
    ASSERT_EQ(run_app(x,
                      adjust_args(manifest, dir / "sessions", id,
                                  {"--observer", "simulated:" + std::to_string(subject)}),
                      dir / "log.txt"),
              0)
        << testing::read_file(dir / "log.txt");
    csvs += " " + (dir / "sessions" / (id + "_s01.csv")).string();
  }
  auto r = testing::run_cli("analyze" + csvs + " -o " + (dir / "report").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  auto results = json::parse(testing::read_file(dir / "report/results.json"));
  EXPECT_EQ(results["n_subjects"], 5);
  EXPECT_TRUE(results["excluded_subjects"].empty());
  EXPECT_DOUBLE_EQ(results["lambda_step"].get<double>(), 0.4);
  ASSERT_EQ(results["fits"].size(), 12u);  // 2 scenes × 2 σ × 3 questions
  // Each fitted threshold lies within the interval-censored answers of its cell.
  auto rows = analysis::read_responses(std::vector<fs::path>{
      dir / "sessions/S1_s01.csv", dir / "sessions/S2_s01.csv", dir / "sessions/S3_s01.csv",
      dir / "sessions/S4_s01.csv", dir / "sessions/S5_s01.csv"});
  for (const auto& fit : results["fits"]) {
    double lo = 1e9, hi = -1e9;
    for (const auto& row : rows)
      if (row.scene == fit["scene"] && row.sigma == fit["sigma"].get<double>() &&
          kQuestionNames[int(row.question)] == fit["question"]) {
        lo = std::min(lo, row.lambda - 0.4);
        hi = std::max(hi, row.lambda);
      }
    const double threshold = fit["threshold"];
    EXPECT_GT(threshold, lo) << fit.dump();
    EXPECT_LE(threshold, hi + 1e-9) << fit.dump();
  }
}

TEST(AdjustGui, RealKeyEventsFromTheXServerDriveTheSession) {
  testing::TempDir dir;
  auto manifest = testing::make_tiny_set(dir, R"({"start": "zero"})");
  testing::XvfbServer x;
  testing::Child app(adjust_args(manifest, dir / "sessions", "P04"), x.display(),
                     (dir / "log.txt").string());
  const std::string xdotool = "DISPLAY=" + x.display() + " xdotool ";
  ASSERT_TRUE(wait_until_ready(dir / "sessions/P04_s01.json", xdotool))
      << testing::read_file(dir / "log.txt");
  for (const char* key : {"Return", "Right", "Right", "Up", "Down", "Return", "Escape", "q"}) {
    ASSERT_EQ(std::system((xdotool + "key " + key).c_str()), 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(120));
  }
  ASSERT_EQ(app.wait(120), 0) << testing::read_file(dir / "log.txt");
  auto rows = analysis::read_responses(dir / "sessions/P04_s01.csv");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_DOUBLE_EQ(rows[0].lambda, 0.8);  // index 0 + 2 + 1 − 1
  auto sidecar = json::parse(testing::read_file(dir / "sessions/P04_s01.json"));
  EXPECT_EQ(sidecar["runs"][0]["end"], "quit");
  ASSERT_EQ(sidecar["runs"][0]["pauses"].size(), 1u);
  EXPECT_EQ(sidecar["runs"][0]["pauses"][0]["quit"], true);
}

TEST(AdjustGui, AHeldKeyRepeatsAtTheAppsRateNotTheXServers) {
  testing::TempDir dir;
  // A 21-value grid (step 0.1), so a held key does not reach the end.
  // The app's interval (200 ms) differs from the X server's default repeat (25 per second).
  auto manifest = testing::make_tiny_set(
      dir, R"({"start": "zero", "repeat": {"delay_ms": 400, "interval_ms": 200}})", 96, 72, 0.1);
  testing::XvfbServer x;
  testing::Child app(adjust_args(manifest, dir / "sessions", "P06"), x.display(),
                     (dir / "log.txt").string());
  const std::string xdotool = "DISPLAY=" + x.display() + " xdotool ";
  ASSERT_TRUE(wait_until_ready(dir / "sessions/P06_s01.json", xdotool))
      << testing::read_file(dir / "log.txt");
  ASSERT_EQ(std::system((xdotool + "key Return").c_str()), 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  // The X server auto-repeats a held key (GLFW reports those as GLFW_REPEAT); the app ignores
  // them and steps once on the press, then every 200 ms after 400 ms.
  ASSERT_EQ(
      std::system((xdotool + "keydown Right && sleep 1.05 && " + xdotool + "keyup Right").c_str()),
      0);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  for (const char* key : {"Return", "Escape", "q"}) {
    ASSERT_EQ(std::system((xdotool + "key " + key).c_str()), 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(150));
  }
  ASSERT_EQ(app.wait(120), 0) << testing::read_file(dir / "log.txt");
  auto table = parse_csv(testing::read_file(dir / "sessions/P06_s01.csv"), "csv");
  ASSERT_EQ(table.rows.size(), 2u);
  const int index = std::stoi(table.rows[1][7]);
  EXPECT_EQ(table.rows[1][column("n_keypresses")], "1");  // one key press
  // 1 step on the press + one at 0.4, 0.6, 0.8 and 1.0 s: 5. The release is timed when the app
  // polls for it, so a late frame can add one or two steps; the X server's rate would give ~10.
  EXPECT_GE(index, 4);
  EXPECT_LE(index, 7);
  int presses = 0, repeats = 0;
  std::istringstream keys(testing::read_file(dir / "sessions/P06_s01.keys.tsv"));
  for (std::string line; std::getline(keys, line);) {
    presses += line.find("\tpress\tright\t") != std::string::npos;
    repeats += line.find("\trepeat\t") != std::string::npos;
  }
  EXPECT_EQ(presses, 1);
  EXPECT_EQ(repeats, index - 1);
  // The X server did repeat the key, and the app dropped those events.
  auto sidecar = json::parse(testing::read_file(dir / "sessions/P06_s01.json"));
  EXPECT_GT(sidecar["runs"][0]["system_key_repeats_ignored"].get<long>(), 0);
}

// A set made for a screen 400 mm wide with 1280 pixels at 570 mm runs on a monitor of that size,
// and is refused on one 5 % wider (the monitor's size given, since Xvfb has no EDID to report).
TEST(AdjustGui, ASetIsShownOnlyAtItsPixelsPerDegree) {
  testing::TempDir dir;
  auto manifest = testing::make_tiny_set(
      dir, "", 96, 72, 0.4,
      R"("screen": {"width_mm": 400, "width_px": 1280, "distance_mm": 570},)");
  testing::XvfbServer x;
  auto run = [&](const std::string& subject, const std::string& width_mm) {
    return run_app(
        x,
        adjust_args(manifest, dir / "sessions", subject,
                    {"--observer", "simulated:1", "--frame-clock", "--monitor-width-mm", width_mm}),
        dir / (subject + ".log"));
  };
  EXPECT_EQ(run("S1", "400"), 0) << testing::read_file(dir / "S1.log");
  EXPECT_EQ(run("S2", "392.5"), 0) << testing::read_file(dir / "S2.log");  // +1.9 %
  ASSERT_EQ(run("S3", "420"), 2);
  const std::string log = testing::read_file(dir / "S3.log");
  EXPECT_EQ(testing::count_lines(log), 1) << log;
  EXPECT_NE(log.find("the set was made for 31.84 pixels per degree at 570 mm, but monitor 0 (1280 "
                     "px, 420 mm wide) gives "
                     "30.32 (-4.8 %"),
            std::string::npos)
      << log;
  EXPECT_FALSE(fs::exists(dir / "sessions/S3_s01.csv"));  // nothing left behind
}

TEST(AdjustGui, AScreenTooSmallForOneToOneIsRefusedWithTheReason) {
  testing::TempDir dir;
  auto manifest = testing::make_tiny_set(dir);
  testing::write_file(dir / "wide.json", R"({"gap_px": 1400})");
  testing::XvfbServer x;
  ASSERT_EQ(run_app(x,
                    adjust_args(manifest, dir / "sessions", "P05",
                                {"--procedure", (dir / "wide.json").string()}),
                    dir / "log.txt"),
            2);
  const std::string log = testing::read_file(dir / "log.txt");
  EXPECT_NE(log.find("at 1:1 scale, but monitor 0 is 1280x1024"), std::string::npos) << log;
  EXPECT_EQ(testing::count_lines(log), 1);
  EXPECT_FALSE(fs::exists(dir / "sessions/P05_s01.csv"));  // nothing left behind
}

}  // namespace
}  // namespace countershade::adjust
