// The forced-choice procedures against their independent references (tests/reference/psychometric):
// every staircase sequence of PsychoPy's StairHandler rules and every QUEST sequence of
// Psychtoolbox, replayed on the recorded answers; and the refusal of bad procedure files.

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/json_reader.h"
#include "formats/responses.h"
#include "procedures/quest.h"
#include "procedures/staircase.h"
#include "test_util.h"

namespace countershade::procedures {
namespace {

using json = nlohmann::json;

std::vector<bool> answers(const std::string& text) {
  std::vector<bool> out;
  for (char c : text) out.push_back(c == '1');
  return out;
}

// The engines' settings read from the reference's own argument objects, as a procedure block's.
StaircaseRules staircase_from(const json& arguments) {
  return read_staircase_rules(ParameterBag::from_json(arguments, "reference", ""));
}
// QuestCreate's empty arguments ([], null here) mean its defaults: they are left out.
QuestParameters quest_from(json arguments) {
  for (auto it = arguments.begin(); it != arguments.end();)
    it = it.value().is_null() ? arguments.erase(it) : std::next(it);
  return read_quest_parameters(ParameterBag::from_json(arguments, "reference", ""));
}

void expect_relative(double got, double expected, double tolerance, const std::string& what) {
  EXPECT_LE(std::abs(got - expected), tolerance * std::abs(expected))
      << what << ": " << got << " against " << expected;
}

TEST(Staircase, EveryReferenceSequenceOfStairHandlersRules) {
  const json expected =
      parse_json_file(testing::reference_path("psychometric/staircase.expected.json"));
  ASSERT_EQ(expected["sequences"].size(), 5u);
  for (const auto& [name, e] : expected["sequences"].items()) {
    const StaircaseRules rules = staircase_from(e["StairHandler"]);
    const CsvTable rows = parse_csv(
        testing::read_file(testing::reference_path("psychometric/" + e["csv"].get<std::string>())),
        name);
    Staircase stair(rules);
    EXPECT_EQ(stair.effective_reversals(), e["effective_nReversals"].get<int>()) << name;
    const auto responses = answers(e["responses"]);
    int at_max = 0, at_min = 0;
    for (size_t t = 0; t < responses.size(); ++t) {
      ASSERT_FALSE(stair.finished()) << name << " trial " << t + 1;
      const auto& row = rows.rows[t + 1];
      expect_relative(stair.next_intensity(), std::stod(row[1]), 1e-9,
                      name + " intensity " + row[0]);
      at_max += rules.max_value && stair.next_intensity() == *rules.max_value;
      at_min += rules.min_value && stair.next_intensity() == *rules.min_value;
      EXPECT_EQ(stair.add_response(responses[t]), row[3] == "1")
          << name << " reversal at trial " << row[0];
    }
    EXPECT_TRUE(stair.finished()) << name;
    EXPECT_EQ(int(responses.size()), e["n_trials"].get<int>()) << name;
    EXPECT_EQ(stair.reversal_trials(), e["reversal_trials"].get<std::vector<int>>()) << name;
    const auto reversals = e["reversal_intensities"].get<std::vector<double>>();
    ASSERT_EQ(stair.reversal_intensities().size(), reversals.size()) << name;
    for (size_t i = 0; i < reversals.size(); ++i)
      expect_relative(stair.reversal_intensities()[i], reversals[i], 1e-9, name);
    expect_relative(stair.estimate(), e["final_estimate"], 1e-9, name + " estimate");
    expect_relative(stair.geometric_estimate(), e["final_estimate_geometric"], 1e-9,
                    name + " geometric estimate");
    expect_relative(stair.next_intensity(), e["next_intensity_after_last_trial"], 1e-9,
                    name + " next intensity");
    EXPECT_EQ(at_max, e["n_at_maxVal"].get<int>()) << name;
    EXPECT_EQ(at_min, e["n_at_minVal"].get<int>()) << name;
  }
}

void expect_quest_state(const Quest& q, const json& e, const std::string& what) {
  EXPECT_NEAR(q.mean(), e["quest_mean"].get<double>(), 1e-9) << what;
  EXPECT_NEAR(q.mode(), e["quest_mode"].get<double>(), 1e-9) << what;
  EXPECT_NEAR(q.sd(), e["quest_sd"].get<double>(), 1e-9) << what;
  EXPECT_NEAR(q.quantile(), e["quest_quantile"].get<double>(), 1e-9) << what;
}

TEST(Quest, EveryReferenceSequenceOfPsychtoolbox) {
  const json expected =
      parse_json_file(testing::reference_path("psychometric/quest.expected.json"));
  ASSERT_EQ(expected["sequences"].size(), 3u);
  for (const auto& [name, e] : expected["sequences"].items()) {
    Quest q(quest_from(e["QuestCreate"]));
    EXPECT_EQ(q.dim(), e["derived"]["dim"].get<int>()) << name;
    EXPECT_NEAR(q.x_threshold(), e["derived"]["xThreshold"].get<double>(), 1e-12) << name;
    EXPECT_NEAR(q.quantile_order(), e["derived"]["quantileOrder"].get<double>(), 1e-12) << name;
    expect_quest_state(q, e["initial"], name + " before the first trial");
    const CsvTable rows = parse_csv(
        testing::read_file(testing::reference_path("psychometric/" + e["csv"].get<std::string>())),
        name);
    ASSERT_EQ(rows.rows.size(), 41u) << name;
    for (size_t t = 1; t < rows.rows.size(); ++t) {
      const auto& row = rows.rows[t];
      EXPECT_NEAR(q.quantile(), std::stod(row[1]), 1e-9) << name << " trial " << row[0];
      q.update(std::stod(row[1]), row[2] == "1");
      const json after = {{"quest_mean", std::stod(row[3])},
                          {"quest_mode", std::stod(row[4])},
                          {"quest_sd", std::stod(row[5])},
                          {"quest_quantile", std::stod(row[6])}};
      expect_quest_state(q, after, name + " after trial " + row[0]);
    }
    expect_quest_state(q, e["final"], name + " after the last trial");
  }
}

// Replay through the command line writes the same sequences as the reference files.
TEST(Replay, CommandLineWritesTheReferenceQuestSequence) {
  testing::TempDir dir;
  const json expected =
      parse_json_file(testing::reference_path("psychometric/quest.expected.json"));
  json procedure = expected["sequences"]["q2_4afc"]["QuestCreate"];
  procedure["type"] = "quest";
  testing::write_file(dir / "quest.json", procedure.dump());
  const auto reference = testing::reference_path("psychometric/quest_q2_4afc.csv");
  const auto run =
      testing::run_cli("simulate --procedure " + (dir / "quest.json").string() + " --responses " +
                       reference.string() + " -o " + (dir / "out.csv").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const CsvTable got = parse_csv(testing::read_file(dir / "out.csv"), "out.csv");
  const CsvTable want = parse_csv(testing::read_file(reference), "reference");
  ASSERT_EQ(got.rows.size(), want.rows.size());
  EXPECT_EQ(got.rows[0], want.rows[0]);
  for (size_t r = 1; r < want.rows.size(); ++r)
    for (size_t c = 1; c < want.rows[r].size(); ++c)
      EXPECT_NEAR(std::stod(got.rows[r][c]), std::stod(want.rows[r][c]), 1e-9)
          << "row " << r << " column " << c;
}

// Each bad procedure exits 2 with one line naming the file and the key.
TEST(Replay, BadProceduresAreRefusedWithOneLine) {
  testing::TempDir dir;
  testing::write_file(dir / "answers.csv", "response\n1\n0\n");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"({"type": "staircase", "startVal": 0.5, "nDown": 0})", "nDown"},
      {R"({"type": "staircase", "startVal": 0.5, "stepSizes": []})", "stepSizes"},
      {R"({"type": "staircase", "startVal": 0.5, "stepType": "lin", "stepSizes": [0.1, -0.1]})",
       "stepSizes"},
      {R"({"type": "staircase", "startVal": 0, "stepType": "log"})", "startVal"},
      {R"({"type": "staircase", "startVal": 0.5, "minVal": 0.6, "maxVal": 1, "stepType": "lin"})",
       "startVal"},
      {R"({"type": "quest", "tGuess": -1, "tGuessSd": 2, "pThreshold": 0.4, "beta": 3.5, "delta": 0.01, "gamma": 0.5})",
       "pThreshold"},
      {R"({"type": "quest", "tGuess": -1, "tGuessSd": 2, "pThreshold": 1.0, "beta": 3.5, "delta": 0.01, "gamma": 0.5})",
       "pThreshold"},
      {R"({"type": "quest", "tGuess": -1, "tGuessSd": 2, "pThreshold": 0.8, "beta": 3.5, "delta": 0.01, "gamma": 0.5, "grian": 1})",
       "grian"},
      {R"({"type": "adaptive"})", "type"},
  };
  for (const auto& [text, key] : cases) {
    testing::write_file(dir / "p.json", text);
    const auto run =
        testing::run_cli("simulate --procedure " + (dir / "p.json").string() + " --responses " +
                         (dir / "answers.csv").string() + " -o " + (dir / "out.csv").string());
    EXPECT_EQ(run.exit_code, 2) << text << "\n" << run.output;
    EXPECT_NE(run.output.find("p.json: " + key), std::string::npos) << run.output;
    EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << run.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.csv"));
  }
  testing::write_file(dir / "p.json", R"({"type": "staircase", "startVal": 0.5})");
  testing::write_file(dir / "answers.csv", "trial,response\n1,1\n2,yes\n");
  const auto run =
      testing::run_cli("simulate --procedure " + (dir / "p.json").string() + " --responses " +
                       (dir / "answers.csv").string() + " -o " + (dir / "out.csv").string());
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(
      run.output.find("answers.csv:3: response: expected 1 or Correct, 0 or Incorrect, got 'yes'"),
      std::string::npos)
      << run.output;
}

}  // namespace
}  // namespace countershade::procedures
