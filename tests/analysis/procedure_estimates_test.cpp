// `analyze` on a QUEST+ session: each condition's posterior, recomputed from the session's trials,
// equals Bayes' rule worked out here by hand on the grid, and stands beside the psychometric fit of
// the same subject and condition.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>

#include "formats/responses.h"
#include "test_util.h"

namespace countershade {
namespace {

namespace fs = std::filesystem;

const std::vector<double> kThresholds = {-1.0, -0.8, -0.6, -0.4, -0.2, 0.0};
const std::vector<double> kSlopes = {2.0, 4.0};
constexpr double kGuess = 0.5, kLapse = 0.02;

// The Weibull on log10 λ, as docs/forced-choice.md writes it.
double psi(double lambda, double t, double b) {
  return 1 - kLapse -
         (1 - kGuess - kLapse) * std::exp(-std::pow(10.0, b * (std::log10(lambda) - t)));
}

struct Trial {
  double lambda;
  bool correct;
};

// The posterior mean of the threshold and of the λ at F = 1/2, by the definition.
std::pair<double, double> posterior_means(const std::vector<Trial>& trials) {
  double total = 0, threshold = 0, half = 0;
  for (double t : kThresholds)
    for (double b : kSlopes) {
      double p = 1;
      for (const Trial& trial : trials)
        p *= trial.correct ? psi(trial.lambda, t, b) : 1 - psi(trial.lambda, t, b);
      total += p;
      threshold += p * t;
      half += p * std::pow(10.0, t) * std::pow(std::log(2.0), 1 / b);
    }
  return {threshold / total, half / total};
}

const std::string kHeader =
    csv_line({"subject", "session", "trial", "scene", "method", "sigma", "lambda", "lambda_index",
              "lambda_requested", "n_afc", "layout", "target", "response", "correct", "rt_ms",
              "procedure", "condition_trial", "set_sha256", "time_utc"});

// One condition's rows (σ, the procedure that ran it), numbered from `first`.
std::string session_rows(const std::vector<Trial>& trials, const std::string& sigma = "0.05",
                         const std::string& procedure = "questplus", size_t first = 1) {
  std::string csv;
  for (size_t i = 0; i < trials.size(); ++i) {
    const std::string l = std::to_string(trials[i].lambda);
    csv += csv_line({"P01", "1", std::to_string(first + i), "cube", "usm3d", sigma, l, "1", l, "2",
                     "spatial", "0", trials[i].correct ? "0" : "1", trials[i].correct ? "1" : "0",
                     "500", procedure, std::to_string(i + 1), std::string(64, 'a'),
                     "2026-01-01T00:00:00.000Z"});
  }
  return csv;
}

std::vector<Trial> simulated_trials(int count, unsigned seed) {
  std::vector<Trial> trials;
  std::mt19937 random(seed);
  const double levels[] = {0.1, 0.2, 0.3, 0.5, 0.8, 1.2};
  for (int i = 0; i < count; ++i) {
    const double lambda = levels[i % 6];
    trials.push_back(
        {lambda, std::uniform_real_distribution<double>(0, 1)(random) < psi(lambda, -0.5, 3)});
  }
  return trials;
}

const char* const kQuestPlus = R"({"type": "questplus", "param_domain": {
      "threshold": [-1.0, -0.8, -0.6, -0.4, -0.2, 0.0], "slope": [2, 4],
      "lower_asymptote": 0.5, "lapse_rate": 0.02}})";

// One session (its trial rows and its sidecar's config), analysed into dir/out.
testing::CommandResult analyze_session(const fs::path& dir, const std::string& rows,
                                       const std::string& config) {
  testing::write_file(dir / "P01_s01.forced-choice.csv", kHeader + rows);
  testing::write_file(dir / "P01_s01.forced-choice.json",
                      R"({"format": 1, "session": 1, "config": )" + config + "}");
  return testing::run_cli("analyze " + (dir / "P01_s01.forced-choice.csv").string() + " -o " +
                          (dir / "out").string() + " --bootstrap 0");
}

TEST(ProcedureEstimates, AQuestPlusSessionsPosteriorIsReportedBesideItsFit) {
  testing::TempDir dir;
  const std::vector<Trial> trials = simulated_trials(120, 5);
  const auto run = analyze_session(dir.path(), session_rows(trials),
                                   std::string(R"({"procedure": )") + kQuestPlus + "}");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const CsvTable table =
      parse_csv(testing::read_file(dir / "out/procedure_estimates.csv"), "estimates");
  std::map<std::string, std::vector<std::string>> by_quantity;
  for (size_t r = 1; r < table.rows.size(); ++r) by_quantity[table.rows[r][6]] = table.rows[r];
  ASSERT_EQ(by_quantity.size(), 5u);  // four parameters and the λ at F = 1/2
  const auto [threshold, half] = posterior_means(trials);
  EXPECT_NEAR(std::stod(by_quantity["threshold"][8]), threshold, 1e-9);
  EXPECT_NEAR(std::stod(by_quantity["lambda_at_half"][8]), half, 1e-9);
  EXPECT_EQ(by_quantity["threshold"][5], "120");
  // The fit of the same subject and condition, as psychometric_fits.csv has it.
  const CsvTable fits = parse_csv(testing::read_file(dir / "out/psychometric_fits.csv"), "fits");
  ASSERT_EQ(fits.rows.size(), 3u);  // header, pooled, P01
  const auto& header = fits.rows[0];
  const size_t column =
      size_t(std::find(header.begin(), header.end(), "threshold") - header.begin());
  ASSERT_LT(column, header.size());
  EXPECT_EQ(fits.rows[2][1], "P01");
  EXPECT_EQ(by_quantity["lambda_at_half"][11], fits.rows[2][column]) << "the fit's threshold";
  EXPECT_EQ(by_quantity["threshold"][11], "NA");
  // The report shows the λ at F = 1/2 beside the fit.
  const std::string page = testing::read_file(dir / "out/forced-choice.html");
  EXPECT_NE(page.find("The procedures' own estimates"), std::string::npos);
  char mean[32];
  std::snprintf(mean, sizeof mean, "<td>%.4f</td>", half);
  EXPECT_NE(page.find(mean), std::string::npos) << mean;
  // Without its sidecar, a session has no procedure estimates.
  fs::remove(dir / "P01_s01.forced-choice.json");
  ASSERT_EQ(testing::run_cli("analyze " + (dir / "P01_s01.forced-choice.csv").string() + " -o " +
                             (dir / "bare").string() + " --bootstrap 0")
                .exit_code,
            0);
  EXPECT_FALSE(fs::exists(dir / "bare/procedure_estimates.csv"));
}

// A session whose block runs constant stimuli and one condition QUEST+ (condition_procedures):
// that condition alone has the posterior, worked out as above from its own trials.
TEST(ProcedureEstimates, OnlyTheConditionThatRanQuestPlusHasItsPosterior) {
  testing::TempDir dir;
  const std::vector<Trial> adaptive = simulated_trials(60, 9), constant = simulated_trials(60, 10);
  const auto run = analyze_session(
      dir.path(),
      session_rows(adaptive) + session_rows(constant, "0.1", "constant", adaptive.size() + 1),
      std::string(R"({"procedure": {"type": "constant",
        "lambdas": [0.1, 0.2, 0.3, 0.5, 0.8, 1.2], "repetitions": 10}, "condition_procedures": [
        {"scene": "cube", "method": "usm3d", "sigma": 0.05, "procedure": )") +
          kQuestPlus + "}]}");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const CsvTable table =
      parse_csv(testing::read_file(dir / "out/procedure_estimates.csv"), "estimates");
  ASSERT_EQ(table.rows.size(), 6u) << "a header and one condition's five quantities";
  for (size_t r = 1; r < table.rows.size(); ++r) EXPECT_EQ(table.rows[r][4], "0.05");
  EXPECT_EQ(table.rows[5][6], "lambda_at_half");
  EXPECT_NEAR(std::stod(table.rows[5][8]), posterior_means(adaptive).second, 1e-9);
}

// Trials whose `procedure` column names another procedure than the session's record (an edited
// record, or a session file beside another session's record): the record's procedure would give
// its estimate to trials it never chose, so the file's estimates are left out with a warning that
// names the row, and the psychometric fits still come.
TEST(ProcedureEstimates, TrialsOfAnotherProcedureThanTheRecordsGetNoEstimate) {
  testing::TempDir dir;
  const std::vector<Trial> trials = simulated_trials(60, 5);
  const auto run = analyze_session(dir.path(), session_rows(trials, "0.05", "staircase"),
                                   std::string(R"({"procedure": )") + kQuestPlus + "}");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("P01_s01.forced-choice.csv:2: procedure: the trial ran 'staircase', "
                            "but " +
                            (dir / "P01_s01.forced-choice.json").string() +
                            ": config.procedure is 'questplus'; its procedure's own estimates are "
                            "left out"),
            std::string::npos)
      << run.output;
  EXPECT_FALSE(fs::exists(dir / "out/procedure_estimates.csv"));
  EXPECT_TRUE(fs::exists(dir / "out/psychometric_fits.csv"));
}

}  // namespace
}  // namespace countershade
