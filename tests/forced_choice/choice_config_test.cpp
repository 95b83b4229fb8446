// Forced-choice configurations that cannot work are refused before any window opens, with one
// line naming the file and key and exit 2; and the experiment refuses them already when the set
// is made. The run's plan: seeded, balanced, and practice only on conditions that change with λ.

#include <gtest/gtest.h>

#include "../adjust/tiny_set.h"
#include "forced_choice/choice_run.h"
#include "procedures/choice_block.h"
#include "runtime/study.h"

namespace countershade::forced_choice {
namespace {

namespace fs = std::filesystem;

constexpr const char* kQuestArguments =
    R"("tGuess": -0.3, "tGuessSd": 1, "beta": 3.5, "delta": 0.01, "gamma": 0.5, "grain": 0.01)";

TEST(ChoiceConfig, ProceduresThatCannotWorkAreOneLineAndExitTwo) {
  testing::TempDir dir;
  const fs::path manifest = testing::make_tiny_set(dir, "", 96, 72, 0.1);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"({"procedure": {"type": "staircase", "startVal": 0.5, "nDown": 0}})", "procedure.nDown"},
      {R"({"procedure": {"type": "staircase", "startVal": 0.5, "stepSizes": []}})",
       "procedure.stepSizes"},
      {std::string(R"({"procedure": {"type": "quest", "pThreshold": 0.45, )") + kQuestArguments +
           "}}",
       "procedure.pThreshold"},
      // log10 λ from 3 to 7: the grid (0.1 … 2) lies far below every threshold QUEST considers.
      {R"({"procedure": {"type": "quest", "tGuess": 5, "tGuessSd": 1, "pThreshold": 0.82, "beta": 3.5, "delta": 0.01, "gamma": 0.5, "range": 4}})",
       "procedure.range"},
      {R"({"procedure": {"type": "constant", "lambdas": [0.25]}})", "procedure.lambdas"},
      {R"({"n_afc": 5, "procedure": {"type": "constant", "lambdas": [0.2]}})", "n_afc"},
      {R"({"procedure": {"type": "constant", "lambdas": [0.2]}, "practice_trials": 2,
           "practice_conditions": [{"scene": "nowhere", "method": "usm3d", "sigma": 0.03}]})",
       "practice_conditions[0]"},
      {R"({"procedure": {"type": "constant", "lambdas": [0.2]}, "condition_procedures": [
           {"scene": "front", "method": "usm3d", "sigma": 0.03,
            "procedure": {"type": "staircase", "startVal": 0.5, "nDown": 0}}]})",
       "condition_procedures[0].procedure.nDown"},
      {R"({"procedure": {"type": "constant", "lambdas": [0.2]}, "condition_procedures": [
           {"scene": "front", "method": "usm3d", "sigma": 0.03, "procedure": {"type": "constant",
            "lambdas": [0.4]}}, {"scene": "front", "method": "usm3d", "sigma": 0.03,
            "procedure": {"type": "constant", "lambdas": [0.6]}}]})",
       "condition_procedures[1].scene"},
      {R"({"procedure": {"type": "constant", "lambdas": [0.2]}, "condition_procedures": [
           {"scene": "front", "method": "usm3d", "sigma": 0.3, "procedure": {"type": "constant",
            "lambdas": [0.4]}}]})",
       "condition_procedures[0]"},
      // A condition the session does not run: its procedure would never be used.
      {R"({"procedure": {"type": "constant", "lambdas": [0.2]}, "conditions": [{"scene": "front",
           "method": "usm3d", "sigma": 0.03}], "condition_procedures": [{"scene": "small",
           "method": "usm3d", "sigma": 0.03, "procedure": {"type": "constant",
           "lambdas": [0.4]}}]})",
       "condition_procedures[0]"},
  };
  for (const auto& [text, key] : cases) {
    testing::write_file(dir / "fc.json", text);
    const auto run =
        testing::run_cli("choose " + manifest.string() + " --subject P01 --sessions " +
                         (dir / "s").string() + " --procedure " + (dir / "fc.json").string());
    EXPECT_EQ(run.exit_code, 2) << text << "\n" << run.output;
    EXPECT_NE(run.output.find(key), std::string::npos) << run.output;
    EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << run.output;
    EXPECT_FALSE(fs::exists(dir / "s" / "P01_s01.forced-choice.csv")) << text;
  }
}

TEST(ChoiceConfig, TheExperimentRefusesABadBlockWhenTheSetIsMade) {
  testing::TempDir dir;
  testing::write_file(dir / "cube.json", testing::kLitCubeScene);
  testing::write_file(
      dir / "experiment.json",
      R"({"version": 1, "scenes": [{"name": "front", "file": "cube.json", "width": 32, "height": 24}],
      "methods": [{"method": "usm3d", "sigma_fraction": [0.03]}],
      "forced_choice": {"procedure": {"type": "staircase", "startVal": 0.5, "nDown": 0}}})");
  const auto run = testing::run_cli("stimuli " + (dir / "experiment.json").string() + " -o " +
                                    (dir / "set").string());
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("experiment.json: forced_choice.procedure.nDown"), std::string::npos)
      << run.output;
}

// Constant stimuli: every listed λ exactly `repetitions` times per condition, each condition's
// targets balanced, the same order for the same seed and another for another seed.
TEST(ChoiceRun, ConstantStimuliAreBalancedAndSeeded) {
  testing::TempDir dir;
  const runtime::Study study =
      runtime::load_study(testing::make_tiny_set(dir, "", 96, 72, 0.1), std::nullopt);
  const ChoiceConfig config = parse_choice_config(
      nlohmann::json::parse(
          R"({"procedure": {"type": "constant", "lambdas": [0.2, 0.6, 1.2], "repetitions": 4}})"),
      "t", "");
  auto trials_of = [&](uint64_t seed) {
    ChoiceRun run(study, config, seed);
    std::vector<std::tuple<int, int, int>> trials;  // condition, λ index, target
    std::map<std::pair<int, int>, int> per_level, per_target;
    while (!run.finished()) {
      const ChoiceTrial t = *run.current();
      trials.push_back({t.condition, t.lambda_index, t.target});
      ++per_level[{t.condition, t.lambda_index}];
      ++per_target[{t.condition, t.target}];
      run.answer(0);
    }
    EXPECT_EQ(per_level.size(), study.conditions.size() * 3);
    for (const auto& [key, count] : per_level) EXPECT_EQ(count, 4);
    for (const auto& [key, count] : per_target) EXPECT_EQ(count, 6);
    return trials;
  };
  EXPECT_EQ(trials_of(1), trials_of(1));
  EXPECT_NE(trials_of(1), trials_of(2));
}

// A condition listed in condition_procedures runs its own procedure; the others run the block's.
TEST(ChoiceRun, AConditionRunsItsOwnProcedureWhereOneIsGiven) {
  testing::TempDir dir;
  const runtime::Study study =
      runtime::load_study(testing::make_tiny_set(dir, "", 96, 72, 0.1), std::nullopt);
  const ChoiceConfig config = parse_choice_config(nlohmann::json::parse(R"({
      "procedure": {"type": "constant", "lambdas": [0.2, 0.6, 1.2], "repetitions": 4},
      "condition_procedures": [{"scene": "small", "method": "usm3d", "sigma": 0.08,
        "procedure": {"type": "constant", "lambdas": [0.5], "repetitions": 2}}]})"),
                                                  "t", "");
  ChoiceRun run(study, config, 3);
  std::map<int, std::map<double, int>> shown;  // condition → λ → trials
  while (!run.finished()) {
    const ChoiceTrial t = *run.current();
    ++shown[t.condition][t.lambda];
    run.answer(0);
  }
  ASSERT_EQ(shown.size(), study.conditions.size());
  for (const auto& [condition, levels] : shown) {
    const auto& c = study.conditions[size_t(condition)];
    const bool own = c.scene == "small" && std::abs(c.sigma - 0.08) < 1e-12;
    const std::map<double, int> expected =
        own ? std::map<double, int>{{0.5, 2}} : std::map<double, int>{{0.2, 4}, {0.6, 4}, {1.2, 4}};
    EXPECT_EQ(levels, expected) << c.scene << " σ " << c.sigma;
    EXPECT_EQ(config.procedure_of(c.scene, c.method, c.sigma).type, "constant");
  }
}

}  // namespace
}  // namespace countershade::forced_choice
