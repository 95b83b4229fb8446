// QUEST+ in the forced-choice app: the real binary on a private Xvfb server, answered by the
// simulated observer on the frame clock. The app chooses each next stimulus on another thread while
// it draws; the trials must be exactly those of the same run made synchronously in-process.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <random>

#include "../adjust/tiny_set.h"
#include "../adjust/x_display.h"
#include "forced_choice/choice_observer.h"
#include "forced_choice/choice_run.h"
#include "formats/responses.h"
#include "runtime/study.h"

namespace countershade::forced_choice {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// A grid of 121 × 24 × 3 × 3 = 26,136 points over the set's 20 λ: large enough that a choice takes
// a noticeable pass over the tables, small enough for a test.
json questplus_block() {
  json threshold = json::array();
  for (int i = 0; i <= 120; ++i) threshold.push_back(-1.5 + 0.0125 * i);
  json slope = json::array();
  for (int i = 0; i < 24; ++i) slope.push_back(1.0 + 0.25 * i);
  return {{"conditions", {{{"scene", "front"}, {"method", "usm3d"}, {"sigma", 0.03}}}},
          {"procedure",
           {{"type", "questplus"},
            {"trials", 30},
            {"param_domain",
             {{"threshold", threshold},
              {"slope", slope},
              {"lower_asymptote", {0.45, 0.5, 0.55}},
              {"lapse_rate", {0, 0.02, 0.04}}}}}}};
}

// The tiny set (λ 0 … 2 in steps of 0.1) with `block` as its forced-choice block.
fs::path make_set(const testing::TempDir& dir, const json& block) {
  return testing::make_tiny_set(dir, "", 96, 72, 0.1, "\"forced_choice\": " + block.dump() + ",");
}

TEST(QuestPlusGui, TheAppsTrialsEqualASynchronousRunAndNoFrameWaits) {
  testing::TempDir dir;
  const json block = questplus_block();
  const fs::path manifest = make_set(dir, block);
  testing::XvfbServer x;
  testing::Child app(
      {COUNTERSHADE_BINARY, "choose", manifest.string(), "--subject", "P01", "--sessions",
       (dir / "s").string(), "--observer", "weibull:0.4,3,11", "--frame-clock"},
      x.display(), (dir / "app.txt").string());
  ASSERT_EQ(app.wait(300), 0) << testing::read_file(dir / "app.txt");
  const CsvTable rows =
      parse_csv(testing::read_file(dir / "s/P01_s01.forced-choice.csv"), "session");
  const json sidecar = json::parse(testing::read_file(dir / "s/P01_s01.forced-choice.json"));
  ASSERT_EQ(rows.rows.size(), 31u);

  // The same session in-process: every choice made before the trial is asked for.
  const runtime::Study study = runtime::load_study(manifest, std::nullopt);
  const ChoiceConfig config = parse_choice_config(block, "test", "");
  ChoiceRun run(study, config, sidecar["seed"].get<uint64_t>());
  const ChoiceObserver observer = parse_choice_observer("weibull:0.4,3,11");
  for (size_t r = 1; r < rows.rows.size(); ++r) {
    ASSERT_FALSE(run.finished());
    const ChoiceTrial t = *run.current();
    EXPECT_EQ(std::stoi(rows.rows[r][7]), t.lambda_index) << "trial " << r;
    EXPECT_EQ(std::stoi(rows.rows[r][11]), t.target) << "trial " << r;
    const int response = observer.respond(t.number, 0, t.lambda, t.target, 2);
    EXPECT_EQ(std::stoi(rows.rows[r][12]), response) << "trial " << r;
    run.answer(response);
  }
  EXPECT_TRUE(run.finished());
  EXPECT_EQ(sidecar["procedures"][0]["state"], run.procedure_state(run.conditions().front()));
  // On the frame clock every frame comes one refresh period after the last, and a key shows on
  // the next frame: no frame waited for a choice.
  const json& frames = sidecar["runs"].back()["frames"];
  EXPECT_EQ(frames["all"]["dropped"], 0) << frames;
  EXPECT_EQ(frames["key_to_frame_frames_max"], 1) << frames;
}

// The rows without the columns that depend on the clock (rt_ms, time_utc).
std::vector<std::vector<std::string>> timeless(const fs::path& csv) {
  std::vector<std::vector<std::string>> rows;
  for (auto row : parse_csv(testing::read_file(csv), csv.string()).rows) {
    row.erase(row.begin() + 14);  // rt_ms
    row.pop_back();               // time_utc
    rows.push_back(row);
  }
  return rows;
}

// Killed at random moments and resumed: the rows and the posterior equal an uninterrupted run's.
TEST(QuestPlusGui, AKilledSessionResumesWithTheSameTrialsAndPosterior) {
  testing::TempDir dir;
  const json block = questplus_block();
  const fs::path manifest = make_set(dir, block);
  testing::XvfbServer x;
  auto args = [&](const std::string& sessions, bool resume) {
    std::vector<std::string> a = {COUNTERSHADE_BINARY,
                                  "choose",
                                  manifest.string(),
                                  "--subject",
                                  "P01",
                                  "--sessions",
                                  (dir / sessions).string(),
                                  "--observer",
                                  "weibull:0.4,3,11"};
    if (resume) a.push_back("--resume");
    return a;
  };
  testing::Child whole(args("whole", false), x.display(), (dir / "whole.txt").string());
  ASSERT_EQ(whole.wait(300), 0) << testing::read_file(dir / "whole.txt");
  std::mt19937 random(3);
  std::uniform_real_distribution<double> kill_after(0.3, 1.2);
  const fs::path csv = dir / "killed/P01_s01.forced-choice.csv";
  const fs::path sidecar = dir / "killed/P01_s01.forced-choice.json";
  int kills = 0;
  for (int launch = 0; launch < 20; ++launch) {
    // As an operator would: a session that has begun (it has its sidecar) is resumed.
    testing::Child app(args("killed", fs::exists(sidecar)), x.display(),
                       (dir / "killed.txt").string());
    if (kills < 4 && app.wait(kill_after(random)) == -1) {
      app.kill_hard();
      ++kills;
      continue;
    }
    ASSERT_EQ(app.wait(300), 0) << testing::read_file(dir / "killed.txt");
    if (testing::read_file(dir / "killed.txt").find("completed;") != std::string::npos) break;
  }
  EXPECT_GE(kills, 1);
  EXPECT_EQ(timeless(csv), timeless(dir / "whole/P01_s01.forced-choice.csv"));
  const auto states = [&](const std::string& sessions) {
    return json::parse(
        testing::read_file(dir / sessions / "P01_s01.forced-choice.json"))["procedures"];
  };
  EXPECT_EQ(states("killed"), states("whole"));
}

}  // namespace
}  // namespace countershade::forced_choice
