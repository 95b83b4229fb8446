// QUEST+ against its independent reference (tests/reference/questplus: five runs of the questplus
// package), replayed on the recorded answers: the same stimulus on every trial, the same entropies
// and estimates. Then the refusal of bad blocks, and QUEST+ converging in a forced-choice run.

#include "procedures/questplus.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "../adjust/tiny_set.h"
#include "core/error.h"
#include "core/json_reader.h"
#include "forced_choice/choice_observer.h"
#include "forced_choice/choice_run.h"
#include "formats/responses.h"
#include "procedures/answer_file.h"
#include "procedures/choice_block.h"
#include "procedures/registry.h"
#include "runtime/study.h"
#include "test_util.h"

namespace countershade::procedures {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

const std::vector<std::string> kCases = {"qp_a_threshold_db", "qp_b_threshold_slope_db",
                                         "qp_c_weibull_log10_4afc", "qp_d_norm_cdf_linear",
                                         "qp_e_prior_mean"};

fs::path case_file(const std::string& name, const std::string& suffix) {
  return testing::reference_path("questplus/" + name + suffix);
}

// |got − expected| ≤ 1e-9·|expected|; an expected 0 within 1e-12 (the reference's README).
void expect_estimate(double got, double expected, const std::string& what) {
  const double tolerance = expected == 0 ? 1e-12 : 1e-9 * std::abs(expected);
  EXPECT_LE(std::abs(got - expected), tolerance) << what << ": " << got << " against " << expected;
}

TEST(QuestPlus, EveryReferenceRunIsReplayedExactly) {
  for (const std::string& name : kCases) {
    SCOPED_TRACE(name);
    const ProcedureBlock block = read_procedure_file(case_file(name, ".json"));
    const std::vector<bool> answers = read_binary_responses(case_file(name, ".responses.csv"));
    const Replay replay = block.settings->replay(answers, name);
    const json expected = parse_json_file(case_file(name, ".expected.json"));
    const CsvTable rows = parse_csv(replay.csv, "replay");
    ASSERT_EQ(rows.rows.size(), expected["trials"].size() + 1);
    EXPECT_EQ(rows.rows[0],
              (std::vector<std::string>{"trial", "intensity", "response", "posterior_entropy"}));
    for (size_t t = 0; t < expected["trials"].size(); ++t) {
      const auto& row = rows.rows[t + 1];
      EXPECT_EQ(std::stod(row[1]), expected["trials"][t]["intensity"].get<double>())
          << "trial " << t + 1;
      EXPECT_EQ(row[2], expected["trials"][t]["response"].get<std::string>());
      EXPECT_NEAR(std::stod(row[3]), expected["entropy_after_each_trial"][t].get<double>(), 1e-9)
          << "trial " << t + 1;
    }
    const json& final = expected["final"];
    EXPECT_NEAR(replay.summary["posterior_entropy"].get<double>(),
                final["posterior_entropy"].get<double>(), 1e-9);
    for (const char* estimate : {"mode", "mean"})
      for (const auto& [parameter, value] : final[estimate].items())
        expect_estimate(replay.summary[estimate][parameter].get<double>(), value.get<double>(),
                        std::string(estimate) + "." + parameter);
  }
}

// `simulate --procedure` writes the same trials and prints the final state as JSON.
TEST(QuestPlus, CommandLineWritesTheReferenceRun) {
  testing::TempDir dir;
  const std::string name = "qp_c_weibull_log10_4afc";
  const auto run = testing::run_cli("simulate --procedure " + case_file(name, ".json").string() +
                                    " --responses " + case_file(name, ".responses.csv").string() +
                                    " -o " + (dir / "out.csv").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const json expected = parse_json_file(case_file(name, ".expected.json"));
  const CsvTable rows = parse_csv(testing::read_file(dir / "out.csv"), "out.csv");
  ASSERT_EQ(rows.rows.size(), 81u);
  EXPECT_EQ(std::stod(rows.rows[80][1]), expected["trials"][79]["intensity"].get<double>());
  const size_t from = run.output.find('{'), to = run.output.rfind('}');  // stdout's JSON
  ASSERT_NE(from, std::string::npos) << run.output;
  const json printed = json::parse(run.output.substr(from, to + 1 - from));
  EXPECT_EQ(printed["mode"], expected["final"]["mode"]);
  EXPECT_NEAR(printed["posterior_entropy"].get<double>(),
              expected["final"]["posterior_entropy"].get<double>(), 1e-9);
  EXPECT_EQ(printed["responses_left"], 0);
}

std::string weibull_block(const std::string& change) {
  json block = json::parse(R"({"type": "questplus", "func": "weibull", "stim_scale": "log10",
      "stim_domain": {"intensity": [-2, -1.5, -1, -0.5, 0]},
      "param_domain": {"threshold": [-2, -1, 0], "slope": [2, 3], "lower_asymptote": 0.5,
                       "lapse_rate": [0, 0.02]}})");
  block.merge_patch(json::parse(change));
  return block.dump();
}

// Each bad block is refused with one line naming the file and the key; on the command line it
// exits 2 and writes nothing.
TEST(QuestPlus, BadBlocksAreRefusedWithOneLine) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"({"func": "logistic"})", "func"},
      {R"({"stim_scale": "ln"})", "stim_scale"},
      {R"({"func": "norm_cdf"})", "stim_scale"},
      {R"({"param_domain": {"threshold": []}})", "param_domain.threshold"},
      {R"({"param_domain": {"slope": [3, 2]}})", "param_domain.slope"},
      {R"({"stim_domain": {"intensity": [0, -1]}})", "stim_domain.intensity"},
      {R"({"prior": {"threshold": [1, 2]}})", "prior.threshold"},
      {R"({"prior": {"slope": [1, -1]}})", "prior.slope"},
      {R"({"prior": {"slope": [0, 0]}})", "prior.slope"},
      {R"({"param_domain": {"lower_asymptote": 0.5, "lapse_rate": [0, 0.5]}})",
       "param_domain.lapse_rate"},
      {R"({"param_domain": {"wobble": 1}})", "param_domain.wobble"},
      {R"({"stim_selection_method": "min_n_entropy"})", "stim_selection_method"},
  };
  for (const auto& [change, key] : cases) {
    try {
      read_procedure_block(json::parse(weibull_block(change)), "p.json", "");
      ADD_FAILURE() << change << " was accepted";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind("p.json: " + key, 0), 0u) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
  testing::TempDir dir;
  testing::write_file(dir / "answers.csv", "response\nCorrect\nIncorrect\n");
  testing::write_file(dir / "p.json", weibull_block(cases.front().first));
  const auto run =
      testing::run_cli("simulate --procedure " + (dir / "p.json").string() + " --responses " +
                       (dir / "answers.csv").string() + " -o " + (dir / "out.csv").string());
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("p.json: func"), std::string::npos) << run.output;
  EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << run.output;
  EXPECT_FALSE(fs::exists(dir / "out.csv"));
}

std::vector<double> steps(double from, double to, size_t n) {
  std::vector<double> out;
  for (size_t i = 0; i < n; ++i) out.push_back(from + (to - from) * double(i) / double(n - 1));
  return out;
}

TEST(QuestPlus, AGridTooLargeForMemoryIsRefusedWithTheSizeItWouldNeed) {
  json block = json::parse(weibull_block("{}"));
  block["param_domain"]["threshold"] = steps(-3, 0, 100000);
  block["param_domain"]["slope"] = steps(1, 5, 10000);
  block["param_domain"]["lapse_rate"] = steps(0, 0.05, 1000);
  try {
    read_procedure_block(block, "p.json", "");
    FAIL() << "a grid of 10^12 points was accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("p.json: param_domain"), std::string::npos) << what;
    EXPECT_NE(what.find("GiB"), std::string::npos) << what;
  }
}

// A session starts every condition's QUEST+ at once, so their memory together must fit before any
// is made: each condition's posterior (points doubles) and the tables (2 × stimuli × points
// doubles) once for every definition on its grid, which the conditions' runs share: the set's 20 λ
// above 0 where the block lists no stimuli, its own stimuli where it does.
TEST(QuestPlus, TheSessionsTablesTogetherMustFitBeforeAnyIsMade) {
  testing::TempDir dir;
  const runtime::Study study =
      runtime::load_study(testing::make_tiny_set(dir, "", 96, 72, 0.1), std::nullopt);
  const double conditions = double(study.conditions.size());
  ASSERT_GT(conditions, 1);
  const auto problem = [&](const json& choice, double limit) {
    return forced_choice::procedure_memory_problem(study, parse_choice_config(choice, "t", ""),
                                                   limit);
  };
  const json listed = json::parse(weibull_block("{}"));  // 5 stimuli, 3 × 2 × 2 = 12 points
  json on_grid = listed;
  on_grid.erase("stim_domain");
  const double posteriors = conditions * 12 * 8;
  const double listed_need = 2 * 5 * 12 * 8 + posteriors, grid_need = 2 * 20 * 12 * 8 + posteriors;
  EXPECT_FALSE(problem({{"procedure", listed}}, listed_need));
  EXPECT_TRUE(problem({{"procedure", listed}}, listed_need - 1));
  EXPECT_FALSE(problem({{"procedure", on_grid}}, grid_need));
  const auto refused = problem({{"procedure", on_grid}}, grid_need - 1);
  ASSERT_TRUE(refused);
  EXPECT_NE(refused->find(std::to_string(study.conditions.size()) + " conditions"),
            std::string::npos)
      << *refused;
  EXPECT_NE(refused->find("GiB"), std::string::npos) << *refused;
  // A condition with a grid of its own (three slopes: 18 points) has tables of its own.
  json own = on_grid;
  own["param_domain"]["slope"] = {2, 3, 4};
  const json front = {{"scene", "front"}, {"method", "usm3d"}, {"sigma", 0.03}};
  json with_own = {{"procedure", on_grid}, {"condition_procedures", {front}}};
  with_own["condition_procedures"][0]["procedure"] = own;
  const double own_need = grid_need - 12 * 8 + 2 * 20 * 18 * 8 + 18 * 8;
  EXPECT_FALSE(problem(with_own, own_need));
  EXPECT_TRUE(problem(with_own, own_need - 1));
  // A session of one condition needs its own tables and posterior alone.
  const json one = {{"procedure", on_grid}, {"conditions", {front}}};
  EXPECT_FALSE(problem(one, 41 * 12 * 8));
  EXPECT_TRUE(problem(one, 41 * 12 * 8 - 1));
}

// Runs of one definition read one copy of the tables while any of them lives, with the numbers
// of runs that each made their own: a server holds a run per participant.
TEST(QuestPlus, RunsOfOneDefinitionShareTheirTables) {
  QuestPlusDefinition d;
  d.stimuli = {-2, -1.5, -1, -0.5, 0};
  d.grids = {std::vector<double>{-2, -1, 0}, {2, 3}, {0.5}, {0, 0.02}};
  const QuestPlus a(d);
  QuestPlus b(d), answered(d);
  EXPECT_TRUE(b.shares_tables_with(a));
  QuestPlusDefinition other_prior = d;  // the tables do not depend on the prior
  other_prior.prior[0] = {1, 2, 1};
  EXPECT_TRUE(QuestPlus(other_prior).shares_tables_with(a));
  QuestPlusDefinition other_stimuli = d;
  other_stimuli.stimuli.pop_back();
  EXPECT_FALSE(QuestPlus(other_stimuli).shares_tables_with(a));
  // One run's answers leave the others' posteriors alone.
  b.update(4, false);
  b.update(0, true);
  answered.update(4, false);
  answered.update(0, true);
  EXPECT_EQ(b.entropy(), answered.entropy());
  EXPECT_EQ(b.next(), answered.next());
  EXPECT_EQ(a.entropy(), QuestPlus(d).entropy());
  EXPECT_NE(a.entropy(), b.entropy());
}

// QUEST+ per condition in a forced-choice run, answered by the Weibull observer: over 50 seeded
// sessions of 80 trials, the posterior mean threshold's median error stays below twice the
// threshold grid's step.
TEST(QuestPlus, AForcedChoiceRunConvergesOnTheObserversThreshold) {
  testing::TempDir dir;
  const runtime::Study study =
      runtime::load_study(testing::make_tiny_set(dir, "", 96, 72, 0.1), std::nullopt);
  const double step = 0.05;
  json block = json::parse(R"({"type": "questplus", "trials": 80,
      "param_domain": {"slope": [1.5, 2.5, 3.5, 4.5], "lower_asymptote": 0.5,
                       "lapse_rate": [0, 0.02, 0.04]}})");
  block["param_domain"]["threshold"] = steps(-1.5, 0.5, 41);  // log10 λ in steps of 0.05
  const json choice = {
      {"procedure", block},
      {"conditions", {{{"scene", "front"}, {"method", "usm3d"}, {"sigma", 0.03}}}}};
  const ChoiceConfig config = parse_choice_config(choice, "t", "");
  const double alpha = 0.45;  // the observer's threshold: log10 0.45 ≈ −0.35
  std::vector<double> errors;
  for (uint64_t seed = 1; seed <= 50; ++seed) {
    forced_choice::ChoiceRun run(study, config, seed);
    const forced_choice::ChoiceObserver observer{alpha, 3, seed, 0, {}};
    while (!run.finished()) {
      const forced_choice::ChoiceTrial t = *run.current();
      run.answer(observer.respond(t.number, 0, t.lambda, t.target, 2));
    }
    const json state = run.procedure_state(run.conditions().front());
    errors.push_back(std::abs(state["mean"]["threshold"].get<double>() - std::log10(alpha)));
  }
  std::nth_element(errors.begin(), errors.begin() + 25, errors.end());
  EXPECT_LT(errors[25], 2 * step);
  EXPECT_GT(*std::max_element(errors.begin(), errors.end()), 0);  // the sessions do differ
}

}  // namespace
}  // namespace countershade::procedures
