// The forced-choice app end to end: the real binary in a real window on a private Xvfb server,
// driven by a key script, the simulated observer and SIGKILL.

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <random>
#include <set>

#include "../adjust/tiny_set.h"
#include "../adjust/x_display.h"
#include "core/image.h"
#include "formats/responses.h"
#include "procedures/quest.h"

namespace countershade::forced_choice {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr const char* kQuest =
    R"({"type": "quest", "tGuess": -0.3, "tGuessSd": 1, "pThreshold": 0.82, "beta": 3.5, "delta": 0.01, "gamma": 0.5,
        "grain": 0.01, "range": 4, "nTrials": )";

// A set over λ 0 … 2 in steps of 0.1 with a forced-choice block.
fs::path make_set(const testing::TempDir& dir, const std::string& block) {
  return testing::make_tiny_set(dir, "", 96, 72, 0.1, "\"forced_choice\": " + block + ",");
}

std::vector<std::string> choose_args(const fs::path& manifest, const fs::path& sessions,
                                     std::vector<std::string> extra) {
  std::vector<std::string> args = {COUNTERSHADE_BINARY, "choose", manifest.string(),
                                   "--subject",         "P01",    "--sessions",
                                   sessions.string()};
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

CsvTable trials_of(const fs::path& sessions) {
  const fs::path csv = sessions / "P01_s01.forced-choice.csv";
  return parse_csv(testing::read_file(csv), csv.string());
}

// Every row against an independent replay: QUEST (checked against Psychtoolbox) updated with the
// log10 of each λ shown; the λ shown is the grid's nearest to 10^(recommendation); the answer is
// the script's key; targets are balanced in pairs.
TEST(ChoiceGui, AScriptedQuestSessionWritesTheExpectedRows) {
  testing::TempDir dir;
  const auto manifest =
      make_set(dir, R"({"conditions": [{"scene": "front", "method": "usm3d", "sigma": 0.03}],
                                          "procedure": )" +
                        std::string(kQuest) + "10}}");
  std::string script = "300 enter\n";
  const std::string keys[] = {"left",  "right", "right", "left",  "left",
                              "right", "left",  "left",  "right", "right"};
  for (const auto& k : keys) script += "100 " + k + "\n";
  testing::write_file(dir / "keys.txt", script);
  testing::XvfbServer x;
  testing::Child app(choose_args(manifest, dir / "sessions",
                                 {"--script", (dir / "keys.txt").string(), "--frame-clock"}),
                     x.display(), (dir / "log.txt").string());
  ASSERT_EQ(app.wait(300), 0) << testing::read_file(dir / "log.txt");
  const CsvTable table = trials_of(dir / "sessions");
  ASSERT_EQ(table.rows.size(), 11u) << testing::read_file(dir / "log.txt");
  procedures::Quest quest({-0.3, 1, 0.82, 3.5, 0.01, 0.5, 0.01, 4.0});
  for (size_t r = 1; r < table.rows.size(); ++r) {
    const auto& row = table.rows[r];
    const double requested = std::pow(10.0, quest.quantile());
    EXPECT_NEAR(std::stod(row[8]), requested, 1e-8) << "trial " << r;
    const double nearest = std::clamp(std::round(requested / 0.1) * 0.1, 0.1, 2.0);
    EXPECT_NEAR(std::stod(row[6]), nearest, 1e-9) << "trial " << r;
    EXPECT_EQ(std::stoi(row[7]), int(std::lround(nearest / 0.1))) << "trial " << r;
    const int response = keys[r - 1] == "left" ? 0 : 1;
    EXPECT_EQ(std::stoi(row[12]), response) << "trial " << r;
    EXPECT_EQ(row[13], std::stoi(row[11]) == response ? "1" : "0") << "trial " << r;
    quest.update(std::log10(std::stod(row[6])), row[13] == "1");
    if (r % 2 == 0) {
      EXPECT_NE(table.rows[r][11], table.rows[r - 1][11]) << "targets balanced in pairs";
    }
  }
  // The run's frame timing, as the adjustment app records it: every key reached the screen.
  const json run =
      json::parse(testing::read_file(dir / "sessions/P01_s01.forced-choice.json"))["runs"][0];
  EXPECT_GT(run["frames"]["all"]["count"].get<int>(), 20) << run;
  EXPECT_EQ(run["frames"]["key_to_frame"]["count"].get<int>(), 11) << run;
  EXPECT_EQ(run["frames"]["key_to_frame_frames_max"].get<int>(), 1) << run;
}

json final_states(const fs::path& sessions) {
  return json::parse(testing::read_file(sessions / "P01_s01.forced-choice.json"))["procedures"];
}

// The rows without the columns that depend on the clock (rt_ms, time_utc).
std::vector<std::vector<std::string>> timeless(const CsvTable& table) {
  std::vector<std::vector<std::string>> rows;
  for (const auto& row : table.rows) rows.push_back({row.begin(), row.begin() + 14});
  for (auto& row : rows) row.push_back(table.rows[&row - &rows[0]][15]);
  return rows;
}

// Ten SIGKILLs at random moments, each followed by --resume: the trials equal an uninterrupted
// run's row for row (none lost, none repeated, the simulated observer answering as it would have
// after the practice), and so does every QUEST's final state.
TEST(ChoiceGui, KilledSessionsResumeWithTheSameTrialsAndQuestState) {
  testing::TempDir dir;
  const auto manifest =
      make_set(dir, R"({"conditions": [{"scene": "front", "method": "usm3d", "sigma": 0.03},
                                                          {"scene": "small", "method": "usm3d", "sigma": 0.08}],
                                          "practice_trials": 2, "procedure": )" +
                        std::string(kQuest) + "12}}");
  testing::XvfbServer x;
  const std::vector<std::string> observer = {"--observer", "weibull:0.4,3,11"};
  std::vector<std::string> at_once = observer;
  at_once.push_back("--frame-clock");  // the same answers: they depend on the trial, not the clock
  testing::Child whole(choose_args(manifest, dir / "whole", at_once), x.display(),
                       (dir / "whole.txt").string());
  ASSERT_EQ(whole.wait(300), 0) << testing::read_file(dir / "whole.txt");

  std::mt19937 random(7);
  std::uniform_real_distribution<double> kill_after(0.0, 0.9);
  int kills = 0;
  const fs::path killed_sidecar = dir / "killed/P01_s01.forced-choice.json";
  auto runs_recorded = [&] {
    return fs::exists(killed_sidecar)
               ? json::parse(testing::read_file(killed_sidecar))["runs"].size()
               : size_t(0);
  };
  for (int launch = 0; launch < 40; ++launch) {
    std::vector<std::string> extra = observer;
    if (fs::exists(killed_sidecar)) extra.push_back("--resume");
    const size_t runs_before = runs_recorded();
    testing::Child app(choose_args(manifest, dir / "killed", extra), x.display(),
                       (dir / "killed.txt").string());
    // The kill's moment is drawn from when the run has registered itself (so the sidecar can know
    // of it): while the stimuli load, between trials, or while a row is written.
    for (int i = 0; i < 2000 && runs_recorded() == runs_before && app.running(); ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    if (kills < 10 && app.wait(kill_after(random)) == -1) {
      app.kill_hard();
      ++kills;
      continue;
    }
    ASSERT_EQ(app.wait(300), 0) << testing::read_file(dir / "killed.txt");
    if (testing::read_file(dir / "killed.txt").find("completed;") != std::string::npos) break;
  }
  EXPECT_EQ(kills, 10);
  const CsvTable killed = trials_of(dir / "killed"), uninterrupted = trials_of(dir / "whole");
  EXPECT_EQ(killed.rows.size(), 1u + 2u * 12u);  // two conditions, 12 QUEST trials each
  EXPECT_EQ(timeless(killed), timeless(uninterrupted));
  EXPECT_EQ(final_states(dir / "killed"), final_states(dir / "whole"));
  const json sidecar = json::parse(testing::read_file(dir / "killed/P01_s01.forced-choice.json"));
  int interrupted = 0;
  for (const auto& run : sidecar["runs"]) interrupted += run["end"] == "interrupted";
  EXPECT_EQ(interrupted, 10);
  EXPECT_EQ(sidecar["runs"].back()["end"], "completed");
}

// Pixels of a stimulus (`image`: its file, position and size in a screenshot's record) that differ
// from the screenshot.
long pixels_differing(const Image& shot, const json& image, const fs::path& set) {
  const Image stimulus = read_image(set / image["file"].get<std::string>());
  EXPECT_EQ(stimulus.width, image["width"].get<int>());
  const int x0 = image["x"], y0 = image["y"];
  long differing = 0;
  for (int y = 0; y < stimulus.height; ++y)
    for (int x = 0; x < stimulus.width; ++x)
      for (int c = 0; c < 3; ++c)
        differing += std::lround(stimulus.at(x, y, c) * 255) !=
                     std::lround(shot.at(x0 + x, y0 + y, c) * 255);
  return differing;
}

// Temporal 2AFC: a screenshot in each interval shows that interval's stimulus pixel for pixel,
// centred on the uniform surround; one interval is the reference, the other the enhanced image.
TEST(ChoiceGui, TheScreenshotsShowBothIntervalsPixelExact) {
  testing::TempDir dir;
  const auto manifest =
      make_set(dir, R"({"layout": "temporal", "interval_frames": 30, "blank_frames": 30,
      "conditions": [{"scene": "front", "method": "usm3d", "sigma": 0.03}],
      "procedure": {"type": "constant", "lambdas": [1.5], "repetitions": 2}})");
  // Enter at 0.3 s starts the trial; interval 1 spans 0–0.5 s of it, the blank 0.5–1 s, interval 2
  // 1–1.5 s.
  testing::write_file(dir / "keys.txt",
                      "300 enter\n250 screenshot\n1000 screenshot\n600 left\n300 close\n");
  testing::XvfbServer x;
  testing::Child app(choose_args(manifest, dir / "sessions",
                                 {"--script", (dir / "keys.txt").string(), "--frame-clock",
                                  "--screenshot", (dir / "shot.png").string()}),
                     x.display(), (dir / "log.txt").string());
  ASSERT_EQ(app.wait(300), 0) << testing::read_file(dir / "log.txt");
  std::set<std::string> shown;
  for (const char* name : {"shot.png", "shot-2.png"}) {
    const json info = json::parse(testing::read_file(dir / (std::string(name) + ".json")));
    ASSERT_EQ(info["images"].size(), 1u) << name << ": " << info.dump();
    EXPECT_EQ(info["interval"],
              std::string(name) == "shot.png" ? "Interval 1 of 2" : "Interval 2 of 2");
    const Image shot = read_image(dir / name);
    const json& image = info["images"][0];
    EXPECT_EQ(image["x"].get<int>(), (shot.width - image["width"].get<int>()) / 2) << "centred";
    EXPECT_EQ(pixels_differing(shot, image, dir / "set"), 0) << name;
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(
          std::lround(shot.at(image["x"].get<int>() - 20, image["y"].get<int>() + 5, c) * 255), 128)
          << "surround";
    shown.insert(image["file"].get<std::string>());
  }
  EXPECT_EQ(shown.size(), 2u);
  EXPECT_TRUE(shown.count("front/reference.png"));
  const CsvTable table = trials_of(dir / "sessions");
  ASSERT_EQ(table.rows.size(), 2u);
  EXPECT_EQ(table.rows[1][6], "1.5");
  EXPECT_EQ(table.rows[1][10], "temporal");
}

// Spatial 3AFC: three images in a row, pixel exact, the enhanced one where the record says; the
// number keys answer, and each row records the key's position.
TEST(ChoiceGui, ThreeAlternativesInARowAnsweredWithNumberKeys) {
  testing::TempDir dir;
  const auto manifest = make_set(
      dir, R"({"n_afc": 3, "conditions": [{"scene": "front", "method": "usm3d", "sigma": 0.03}],
      "procedure": {"type": "constant", "lambdas": [2], "repetitions": 3}})");
  testing::write_file(dir / "keys.txt",
                      "300 enter\n100 screenshot\n100 1\n100 2\n100 3\n200 enter\n");
  testing::XvfbServer x;
  testing::Child app(choose_args(manifest, dir / "sessions",
                                 {"--script", (dir / "keys.txt").string(), "--frame-clock",
                                  "--screenshot", (dir / "shot.png").string()}),
                     x.display(), (dir / "log.txt").string());
  ASSERT_EQ(app.wait(300), 0) << testing::read_file(dir / "log.txt");
  const json info = json::parse(testing::read_file(dir / "shot.png.json"));
  ASSERT_EQ(info["images"].size(), 3u) << info.dump();
  const Image shot = read_image(dir / "shot.png");
  for (int i = 0; i < 3; ++i) {
    const json& image = info["images"][size_t(i)];
    EXPECT_EQ(pixels_differing(shot, image, dir / "set"), 0) << i;
    EXPECT_EQ(image["file"] == "front/reference.png", i != info["target"].get<int>()) << i;
  }
  const CsvTable table = trials_of(dir / "sessions");
  ASSERT_EQ(table.rows.size(), 4u) << testing::read_file(dir / "log.txt");
  std::set<std::string> targets;
  for (size_t r = 1; r < 4; ++r) {
    EXPECT_EQ(table.rows[r][9], "3");
    EXPECT_EQ(table.rows[r][12], std::to_string(r - 1)) << "the key pressed";
    EXPECT_EQ(table.rows[r][13], table.rows[r][11] == table.rows[r][12] ? "1" : "0");
    targets.insert(table.rows[r][11]);
  }
  EXPECT_EQ(targets.size(), 3u) << "each position once in a block of three";
}

}  // namespace
}  // namespace countershade::forced_choice
