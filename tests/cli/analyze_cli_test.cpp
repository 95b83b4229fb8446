// End-to-end tests of `countershade analyze` and `countershade simulate` through the real binary.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "test_util.h"

namespace countershade {
namespace {

using testing::count_lines;
using testing::run_cli;

TEST(AnalyzeCli, WritesResultsTablesFiguresAndReport) {
  testing::TempDir dir;
  std::string study = testing::reference_path("analysis/study_a.csv").string();
  auto r = run_cli("analyze " + study + " -o " + (dir / "out").string() + " --bootstrap 20");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : {"results.json", "descriptives.csv", "anova.csv", "pairwise.csv", "fits.csv",
                        "clusters.csv", "fig12_questions_by_scene.svg", "fig13_lambda_by_sigma.svg",
                        "fits.svg", "dendrogram.svg", "report.html"})
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / f)) << f;
  auto results = nlohmann::json::parse(testing::read_file(dir / "out/results.json"));
  EXPECT_EQ(results["n_subjects"], 15);
  EXPECT_TRUE(results["fits"][0].contains("ci_low"));
  std::string report = testing::read_file(dir / "out/report.html");
  EXPECT_NE(report.find("F(2, 28) = 505.41, p &lt; .001, η²G = .90"), std::string::npos);
  EXPECT_NE(report.find("<svg"), std::string::npos);  // self-contained: figures inline
  std::string anova = testing::read_file(dir / "out/anova.csv");
  EXPECT_EQ(anova.rfind("model,effect,df1,df2,F,p,ges", 0), 0u) << anova.substr(0, 80);
}

// study_b has 11 subjects, too few for the 12 contrasts of question × scene × σ: R reports no
// sphericity test and no corrections for that effect, and the tables leave those cells empty.
TEST(AnalyzeCli, AnEffectWithMoreContrastsThanSubjectsHasNoSphericityTest) {
  testing::TempDir dir;
  std::string study = testing::reference_path("analysis/study_b.csv").string();
  auto r = run_cli("analyze " + study + " -o " + (dir / "out").string() + " --bootstrap 0");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(
      r.output.find(
          "question:scene:sigma: 11 subjects are too few for a sphericity test of 12 contrasts"),
      std::string::npos)
      << r.output;
  const std::string anova = testing::read_file(dir / "out/anova.csv");
  const size_t row = anova.find("question*scene*sigma,question:scene:sigma,12,120,");
  ASSERT_NE(row, std::string::npos) << anova;
  EXPECT_NE(anova.find(",,,,,,\n", row), std::string::npos)
      << anova.substr(row, 200);  // six empty cells
  EXPECT_EQ(anova.find("nan"), std::string::npos) << anova;
  EXPECT_EQ(testing::read_file(dir / "out/report.html").find("nan<"), std::string::npos);
}

// Three subjects who all give the same answers, λ_Low = `low`, in two scenes × two σ.
std::string same_answers_csv(const std::string& low) {
  std::string csv = "subject,scene,sigma,question,lambda,lambda_step\n";
  for (const char* subject : {"S1", "S2", "S3"})
    for (const char* scene : {"a", "b"})
      for (const char* sigma : {"0.1", "0.2"})
        for (const auto& [question, lambda] :
             {std::pair<std::string, std::string>{"low", low}, {"best", "0.6"}, {"high", "1.2"}})
          csv += std::string(subject) + "," + scene + "," + sigma + "," + question + "," + lambda +
                 ",0.05\n";
  return csv;
}

// Every subject gives the same answers: no error variance, so F and t are infinite (or 0 / 0).
// Boost's distributions threw on them and the analysis failed (exit 1); R's pf gives p = 0 (NA for
// 0 / 0). The tables say Inf and NA, and a warning names each statistic.
TEST(AnalyzeCli, AnswersThatDoNotVaryBetweenSubjectsGiveInfAndNaWithWarnings) {
  testing::TempDir dir;
  auto file = testing::write_file(dir / "same.csv", same_answers_csv("0.3"));
  auto r = run_cli("analyze " + file.string() + " -o " + (dir / "out").string() + " --bootstrap 0");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("anova question: F = Inf, the answers do not vary between subjects"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("pairwise best − low: t = Inf"), std::string::npos) << r.output;
  const std::string anova = testing::read_file(dir / "out/anova.csv");
  EXPECT_NE(anova.find("question*scene*sigma,question,2,4,Inf,0,1,"), std::string::npos) << anova;
  EXPECT_NE(anova.find("question*scene*sigma,scene,1,2,NA,NA,NA,"), std::string::npos) << anova;
  EXPECT_NE(testing::read_file(dir / "out/report.html").find("∞"), std::string::npos);
}

// One scene, two σ, five subjects whose answers differ: the ANOVA is question × σ. Its σ effect,
// with two levels, is the square of the paired t of the subjects' means over questions at the two
// σ, computed here by hand.
TEST(AnalyzeCli, OneSceneStillGetsTheQuestionBySigmaAnova) {
  testing::TempDir dir;
  std::string csv = "subject,scene,sigma,question,lambda,lambda_step\n";
  const double low[5][2] = {{0.2, 0.3}, {0.25, 0.3}, {0.2, 0.35}, {0.3, 0.3}, {0.25, 0.4}};
  std::vector<double> jnd_difference;  // per subject: mean JND at σ 0.1 − at σ 0.2
  for (int i = 0; i < 5; ++i) {
    double means[2] = {0, 0};
    for (int g = 0; g < 2; ++g) {
      const double best = low[i][g] * (2 + 0.05 * i * (g + 1) / low[i][g]);
      const double high = low[i][g] * 4 + 0.05 * (i % 2) + 0.05 * g;
      const double answers[3] = {low[i][g], best, high};
      for (int q = 0; q < 3; ++q) {
        const double lambda = std::round(answers[q] / 0.05) * 0.05;
        csv += "S" + std::to_string(i) + ",only," + (g ? "0.2" : "0.1") + "," +
               (q == 0   ? "low"
                : q == 1 ? "best"
                         : "high") +
               "," + std::to_string(lambda) + ",0.05\n";
        means[g] += lambda / (std::round(low[i][g] / 0.05) * 0.05) / 3;
      }
    }
    jnd_difference.push_back(means[0] - means[1]);
  }
  double mean = 0, ss = 0;
  for (double d : jnd_difference) mean += d / 5;
  for (double d : jnd_difference) ss += (d - mean) * (d - mean);
  const double t = mean / std::sqrt(ss / 4 / 5);
  auto file = testing::write_file(dir / "one.csv", csv);
  auto r = run_cli("analyze " + file.string() + " -o " + (dir / "out").string() + " --bootstrap 0");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  auto results = nlohmann::json::parse(testing::read_file(dir / "out/results.json"));
  std::map<std::string, nlohmann::json> rows;
  for (const auto& row : results["anova"]) rows[row["effect"]] = row;
  ASSERT_EQ(rows.size(), 3u) << results["anova"].dump();
  EXPECT_EQ(rows["question"]["model"], "question*sigma");
  EXPECT_EQ(rows["question:sigma"]["df1"], 2);
  EXPECT_EQ(rows["sigma"]["df2"], 4);
  EXPECT_NEAR(rows["sigma"]["F"].get<double>(), t * t, 1e-9 * t * t);
  ASSERT_EQ(results["anova_best_sigma"].size(), 1u);
  EXPECT_EQ(results["anova_best_sigma"][0]["model"], "sigma (best only)");
  const std::string report = testing::read_file(dir / "out/report.html");
  EXPECT_NE(report.find("ANOVA: question*sigma"), std::string::npos);
  EXPECT_NE(report.find("<b>sigma</b> on λ_Best"), std::string::npos);
}

// Every answer of a cell at one grid step: the spread is not identified, so the cell has no
// standard error and keeps the step as its threshold; an empty table still has its header.
TEST(AnalyzeCli, AnswersAllAtOneStepHaveNoStandardErrorAndKeepTheStep) {
  testing::TempDir dir;
  std::string csv = "subject,scene,sigma,question,lambda,lambda_step\n";
  for (const char* subject : {"S1", "S2", "S3", "S4"})
    for (const auto& [question, lambda] :
         {std::pair{"low", "0.3"}, {"best", "0.6"}, {"high", "1.2"}})
      csv += std::string(subject) + ",only,0.1," + question + "," + lambda + ",0.05\n";
  auto file = testing::write_file(dir / "step.csv", csv);
  auto r = run_cli("analyze " + file.string() + " -o " + (dir / "out").string() + " --bootstrap 0");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  auto results = nlohmann::json::parse(testing::read_file(dir / "out/results.json"));
  for (const auto& fit : results["fits"]) {
    EXPECT_FALSE(fit["identified"].get<bool>()) << fit.dump();
    EXPECT_TRUE(fit["log_threshold_se"].is_null()) << fit.dump();
  }
  EXPECT_NEAR(results["fits"][0]["threshold"].get<double>(), 0.3, 1e-12);
  EXPECT_NE(r.output.find("every answer at one grid step"), std::string::npos) << r.output;
  EXPECT_EQ(testing::read_file(dir / "out/anova_best_sigma.csv"), "model,effect,df1,df2,F,p,ges\n");
  EXPECT_NE(testing::read_file(dir / "out/report.html").find("One σ value"), std::string::npos);
}

TEST(AnalyzeCli, SimulatedStudyRoundTripsWithMethodBlocks) {
  testing::TempDir dir;
  auto r = run_cli("simulate -o " + (dir / "sim.csv").string() + " --subjects 12 --seed 3");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_cli("analyze " + (dir / "sim.csv").string() + " -o " + (dir / "out").string() +
              " --bootstrap 0 --no-figures");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  auto results = nlohmann::json::parse(testing::read_file(dir / "out/results.json"));
  EXPECT_EQ(results["method"], "simulated");
  EXPECT_EQ(results["n_subjects"], 12);
  EXPECT_FALSE(std::filesystem::exists(dir / "out/report.html"));
}

TEST(AnalyzeCli, BadInputExitsWithTwoAndOneLine) {
  testing::TempDir dir;
  auto missing_column =
      testing::write_file(dir / "a.csv", "subject,scene,sigma,question\nS1,a,0.1,low\n");
  auto no_step =
      testing::write_file(dir / "b.csv", "subject,scene,sigma,question,lambda\nS1,a,0.1,low,0.5\n");
  auto no_low = testing::write_file(dir / "c.csv", same_answers_csv("0"));
  struct Case {
    std::string args, expected;
  } cases[] = {
      {missing_column.string() + " -o " + (dir / "o").string(), "missing column 'lambda'"},
      {no_step.string() + " -o " + (dir / "o").string(), "--lambda-step"},
      {(dir / "none.csv").string() + " -o " + (dir / "o").string(), "no such file"},
      {no_step.string() + " -o " + (dir / "o").string() + " --model gamma", "--model"},
      {no_step.string() + " -o " + (dir / "o").string() + " --lambda-step 0.05",
       "b.csv: only 0 subjects have answers in every cell"},
      {no_step.string() + " -o " + (dir / "b.csv/o").string() + " --lambda-step 0.05",
       "is not a folder"},
      // The group mean of λ_Low is 0 there: every JND would be λ / 0 (it gave tables of NA and
      // Inf).
      {no_low.string() + " -o " + (dir / "o").string() + " --normalization group",
       "c.csv: scene a, sigma 0.1: every λ_Low is 0, so --normalization group has no JND scale "
       "there"},
  };
  for (const auto& c : cases) {
    auto r = run_cli("analyze " + c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.output;
    EXPECT_EQ(count_lines(r.output), 1) << r.output;
    EXPECT_NE(r.output.find(c.expected), std::string::npos) << r.output;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "o")) << "a failed analysis leaves no output folder";
}

}  // namespace
}  // namespace countershade
