// Parameter recovery: simulated studies with a known threshold are recovered within their
// bootstrap confidence intervals in at least 90 of 100 seeded runs, also when a third of the
// answers hit the top of the grid.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "analysis/fit.h"
#include "analysis/simulate.h"

namespace countershade::analysis {
namespace {

// The answers to one question as the analysis fits them (methods.md, threshold fits); with
// `ceiling` false, answers at the top count as exact, as earlier versions fitted them.
std::vector<AnswerInterval> intervals_of(const std::vector<Response>& rows, Question q,
                                         bool ceiling = true) {
  std::vector<AnswerInterval> out;
  for (const auto& r : rows)
    if (r.question == q)
      out.push_back(
          answer_interval(r.lambda, r.lambda_index, r.lambda_step, ceiling ? r.lambda_max : 0.0));
  return out;
}

AnswerGrid grid_of(const SimulationDesign& d) {
  return {d.lambda_min, d.lambda_step, d.lambda_max};
}

std::vector<AnswerInterval> on_grid(const std::vector<double>& answers, double step) {
  std::vector<AnswerInterval> out;
  for (double a : answers) out.push_back(answer_interval(a, -1, step, 0.0));
  return out;
}

TEST(Recovery, KnownThresholdLiesInTheBootstrapIntervalInAtLeast90Of100Studies) {
  SimulationDesign design;
  design.subjects = 30;
  design.scenes = {"chamfer"};
  design.sigmas = {0.02};
  // λ_Low: ln λ = ln 0.3 + subject offset (sd 0.25) + answer noise (sd 0.15), so the population
  // of answers is log-normal with median 0.3 before the grid quantises it.
  const double truth = design.low;
  int covered = 0, runs = 0;
  double sum_threshold = 0;
  for (uint64_t seed = 1; seed <= 100; ++seed) {
    design.seed = seed;
    const auto answers = intervals_of(simulate_responses(design), Question::low);
    ASSERT_EQ(answers.size(), 30u);
    Fit fit = fit_threshold(answers, ThresholdModel::log_normal);
    ASSERT_TRUE(fit.converged) << "seed " << seed;
    bootstrap_threshold(fit, grid_of(design), 200, seed);
    ASSERT_GT(fit.bootstrap, 190);
    covered += fit.ci_low <= truth && truth <= fit.ci_high;
    sum_threshold += fit.threshold;
    ++runs;
  }
  EXPECT_GE(covered, 90) << covered << " of " << runs;
  EXPECT_NEAR(sum_threshold / runs, truth, 0.01) << "the estimate is unbiased on average";
}

// λ_High with its median at 0.8 × λ_max: ln λ has SD 0.52 over the population (subjects 0.45,
// answers 0.26), so about a third of the answers lie beyond the grid and are given at its top.
// Right-censored there, the fit's intervals cover the truth; fitted as exact answers at the top
// (earlier versions), the median is biased low and the intervals miss it.
TEST(Recovery, ThresholdNearTheTopOfTheGridIsRecoveredWithRightCensoring) {
  SimulationDesign design;
  design.subjects = 30;
  design.scenes = {"chamfer"};
  design.sigmas = {0.02};
  design.low_subject_sd = 0.45;
  design.answer_sd = 0.26;
  const double truth = design.low * design.high_jnd;  // λ_High's median at the first σ
  design.lambda_max = truth / 0.8;
  int covered = 0, covered_bootstrap = 0, covered_naive = 0, censored = 0, answers_seen = 0;
  for (uint64_t seed = 1; seed <= 100; ++seed) {
    design.seed = seed;
    const auto rows = simulate_responses(design);
    Fit fit = fit_threshold(intervals_of(rows, Question::high), ThresholdModel::log_normal);
    Fit naive =
        fit_threshold(intervals_of(rows, Question::high, false), ThresholdModel::log_normal);
    ASSERT_TRUE(fit.converged) << "seed " << seed;
    censored += int(fit.right_censored);
    answers_seen += int(fit.n);
    auto wald_covers = [&](const Fit& f) {
      return std::abs(f.log_threshold - std::log(truth)) <= 1.96 * f.log_threshold_se;
    };
    covered += wald_covers(fit);
    covered_naive += wald_covers(naive);
    bootstrap_threshold(fit, grid_of(design), 100, seed);
    covered_bootstrap += fit.ci_low <= truth && truth <= fit.ci_high;
  }
  const double share = double(censored) / answers_seen;
  EXPECT_GT(share, 0.25);
  EXPECT_LT(share, 0.42);
  EXPECT_GE(covered, 90) << "Wald intervals of the censored fit";
  EXPECT_GE(covered_bootstrap, 90) << "bootstrap intervals of the censored fit";
  EXPECT_LT(covered_naive, 90) << "the fit without right-censoring covers the truth "
                               << covered_naive << " times";
  std::printf(
      "right-censored answers %.0f %%; 95 %% CI covers the true median: censored fit %d/100 "
      "(Wald), "
      "%d/100 (bootstrap); without censoring %d/100\n",
      100 * share, covered, covered_bootstrap, covered_naive);
}

TEST(Recovery, SameSeedGivesTheSameBootstrapInterval) {
  const auto answers = on_grid({0.25, 0.3, 0.3, 0.35, 0.2, 0.4, 0.3, 0.25, 0.45, 0.3}, 0.05);
  Fit a = fit_threshold(answers, ThresholdModel::log_normal), b = a;
  bootstrap_threshold(a, {0.0, 0.05}, 100, 7);
  bootstrap_threshold(b, {0.0, 0.05}, 100, 7);
  EXPECT_EQ(a.ci_low, b.ci_low);
  EXPECT_EQ(a.ci_high, b.ci_high);
  EXPECT_LT(a.ci_low, a.threshold);
  EXPECT_GT(a.ci_high, a.threshold);
}

// Found by the analysis fuzzer: a fit whose location ran off to infinity drew NaN thresholds, and
// a NaN became a grid index (undefined behaviour). Such a model is not resampled.
TEST(Recovery, AModelThatRanOffToInfinityIsNotBootstrapped) {
  const auto answers = on_grid({0.25, 0.3, 0.3, 0.35, 0.2}, 0.05);
  for (ThresholdModel model :
       {ThresholdModel::log_normal, ThresholdModel::weibull, ThresholdModel::logistic}) {
    Fit fit = fit_threshold(answers, model);
    fit.location = -std::numeric_limits<double>::infinity();
    bootstrap_threshold(fit, {0.0, 0.05, 0.5}, 20, 3);
    EXPECT_EQ(fit.bootstrap, 0) << threshold_model_name(model);
    EXPECT_TRUE(std::isnan(fit.ci_low)) << threshold_model_name(model);
  }
}

TEST(Recovery, WeibullAndLogisticModelsFitTheirOwnData) {
  // Answers of a known logistic population on a 0.05 grid: threshold (median) 1.0.
  std::vector<double> answers;
  for (int i = 1; i < 200; ++i) {
    double u = i / 200.0, x = 1.0 + 0.1 * std::log(u / (1 - u));
    answers.push_back(std::max(1.0, std::ceil(x / 0.05 - 1e-9)) * 0.05);
  }
  Fit logistic = fit_threshold(on_grid(answers, 0.05), ThresholdModel::logistic);
  EXPECT_TRUE(logistic.converged);
  EXPECT_NEAR(logistic.threshold, 1.0, 0.02);
  EXPECT_NEAR(logistic.scale, 0.1, 0.01);
  Fit weibull = fit_threshold(on_grid(answers, 0.05), ThresholdModel::weibull);
  EXPECT_TRUE(weibull.converged);
  EXPECT_NEAR(weibull.threshold, 1.0, 0.05);  // a different shape, but the same median region
  EXPECT_NEAR(fit_cdf(logistic, logistic.threshold), 0.5, 1e-9);
  EXPECT_NEAR(fit_cdf(weibull, weibull.threshold), 0.5, 1e-9);
}

}  // namespace
}  // namespace countershade::analysis
