// `analyze` on forced-choice trial tables: psychometric_fits.csv in the documented column order
// with psyphy's thresholds, the results.json block and the figures; a bad trial field is one line
// and exit 2.

#include <gtest/gtest.h>

#include "core/json_reader.h"
#include "formats/responses.h"
#include "test_util.h"

namespace countershade {
namespace {

TEST(ForcedChoiceCli, AnalyzeWritesThePsychometricFitsOfATrialTable) {
  testing::TempDir dir;
  const auto data = testing::reference_path("psychometric/afc4_a.csv");
  const auto run = testing::run_cli("analyze " + data.string() + " -o " + (dir / "out").string() +
                                    " --bootstrap 200");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const CsvTable table =
      parse_csv(testing::read_file(dir / "out/psychometric_fits.csv"), "psychometric_fits.csv");
  const std::vector<std::string> first = {
      "scope",     "subject",      "scene", "label",      "sigma",    "model", "lapse", "guess",
      "threshold", "threshold_se", "slope", "lapse_rate", "deviance", "df",    "aic",   "n_trials"};
  ASSERT_GE(table.rows[0].size(), first.size());
  EXPECT_EQ(
      std::vector<std::string>(table.rows[0].begin(), table.rows[0].begin() + long(first.size())),
      first);
  const nlohmann::json expected =
      parse_json_file(testing::reference_path("psychometric/afc4_a.expected.json"));
  int pooled = 0;
  for (size_t r = 1; r < table.rows.size(); ++r) {
    const auto& row = table.rows[r];
    if (row[0] != "pooled") continue;
    const auto& e = expected["fits"]["mafc.cloglog"]["pooled"][row[2] + "|" + row[4]];
    ASSERT_TRUE(e.is_object()) << row[2] << " " << row[4];
    EXPECT_NEAR(std::stod(row[8]), e["threshold"].get<double>(),
                1e-6 * e["threshold"].get<double>())
        << row[2];
    EXPECT_NEAR(std::stod(row[10]), e["slope"].get<double>(), 1e-6 * e["slope"].get<double>())
        << row[2];
    EXPECT_EQ(row[7], "0.25");
    EXPECT_LE(std::stod(row[16]), std::stod(row[8]));  // the CI holds the estimate
    EXPECT_GE(std::stod(row[17]), std::stod(row[8]));
    ++pooled;
  }
  EXPECT_EQ(pooled, 2);
  const nlohmann::json results = parse_json_file(dir / "out/results.json");
  EXPECT_EQ(results["forced_choice"]["fits"].size(), table.rows.size() - 1);
  EXPECT_EQ(results["forced_choice"]["trials"].get<int>(), 1920);
  for (const auto& [scene, file] : results["forced_choice"]["figures"].items())
    EXPECT_NE(testing::read_file(dir / "out" / file.get<std::string>()).find("<svg"),
              std::string::npos)
        << scene;
}

TEST(ForcedChoiceCli, TheSameSeedGivesTheSameBootstrap) {
  testing::TempDir dir;
  const auto data = testing::reference_path("psychometric/afc4_a.csv").string();
  for (const char* out : {"a", "b"})
    ASSERT_EQ(testing::run_cli("analyze " + data + " -o " + (dir / out).string() +
                               " --bootstrap 100 --seed 9")
                  .exit_code,
              0);
  EXPECT_EQ(testing::read_file(dir / "a/psychometric_fits.csv"),
            testing::read_file(dir / "b/psychometric_fits.csv"));
}

TEST(ForcedChoiceCli, BadTrialFieldsAreOneLineAndExitTwo) {
  testing::TempDir dir;
  const std::string header = "subject,scene,sigma,lambda,correct,n_afc\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"S01,dice,0.01,0.2,2,2\n", "trials.csv:2: correct: expected 0 or 1, got '2'"},
      {"S01,dice,0.01,0.2,yes,2\n", "trials.csv:2: correct: expected 0 or 1, got 'yes'"},
      {"S01,dice,0.01,0,1,2\n", "trials.csv:2: lambda: must be above 0"},
      {"S01,dice,0.01,0.2,1,1\n", "trials.csv:2: n_afc: expected a whole number"},
      {"S01,dice,0.01,abc,1,2\n", "trials.csv:2: lambda: expected a number, got 'abc'"},
  };
  for (const auto& [row, message] : cases) {
    testing::write_file(dir / "trials.csv", header + "S01,dice,0.01,0.1,1,2\n" + row);
    // the bad row is line 3 (after the header and one good row)
    std::string want = message;
    want.replace(want.find(":2:"), 3, ":3:");
    const auto run = testing::run_cli("analyze " + (dir / "trials.csv").string() + " -o " +
                                      (dir / "out").string());
    EXPECT_EQ(run.exit_code, 2) << row << run.output;
    EXPECT_NE(run.output.find(want), std::string::npos) << run.output;
    EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << run.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out"));
  }
}

}  // namespace
}  // namespace countershade
