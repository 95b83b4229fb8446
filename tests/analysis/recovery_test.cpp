// Parameter recovery: simulated studies with a known threshold are recovered within their
// bootstrap confidence intervals in at least 90 of 100 seeded runs.

#include <gtest/gtest.h>

#include <cmath>

#include "analysis/fit.h"
#include "analysis/simulate.h"

namespace countershade::analysis {
namespace {

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
    std::vector<double> answers;
    for (const auto& r : simulate_responses(design))
      if (r.question == Question::low) answers.push_back(r.lambda);
    ASSERT_EQ(answers.size(), 30u);
    Fit fit = fit_threshold(answers, design.lambda_step, FitModel::lognormal);
    ASSERT_TRUE(fit.converged) << "seed " << seed;
    bootstrap_threshold(fit, design.lambda_step, 200, seed);
    ASSERT_GT(fit.bootstrap, 190);
    covered += fit.ci_low <= truth && truth <= fit.ci_high;
    sum_threshold += fit.threshold;
    ++runs;
  }
  EXPECT_GE(covered, 90) << covered << " of " << runs;
  EXPECT_NEAR(sum_threshold / runs, truth, 0.01) << "the estimate is unbiased on average";
}

TEST(Recovery, SameSeedGivesTheSameBootstrapInterval) {
  std::vector<double> answers = {0.25, 0.3, 0.3, 0.35, 0.2, 0.4, 0.3, 0.25, 0.45, 0.3};
  Fit a = fit_threshold(answers, 0.05, FitModel::lognormal), b = a;
  bootstrap_threshold(a, 0.05, 100, 7);
  bootstrap_threshold(b, 0.05, 100, 7);
  EXPECT_EQ(a.ci_low, b.ci_low);
  EXPECT_EQ(a.ci_high, b.ci_high);
  EXPECT_LT(a.ci_low, a.threshold);
  EXPECT_GT(a.ci_high, a.threshold);
}

TEST(Recovery, WeibullAndLogisticModelsFitTheirOwnData) {
  // Answers of a known logistic population on a 0.05 grid: threshold (median) 1.0.
  std::vector<double> answers;
  for (int i = 1; i < 200; ++i) {
    double u = i / 200.0, x = 1.0 + 0.1 * std::log(u / (1 - u));
    answers.push_back(std::max(1.0, std::ceil(x / 0.05 - 1e-9)) * 0.05);
  }
  Fit logistic = fit_threshold(answers, 0.05, FitModel::logistic);
  EXPECT_TRUE(logistic.converged);
  EXPECT_NEAR(logistic.threshold, 1.0, 0.02);
  EXPECT_NEAR(logistic.scale, 0.1, 0.01);
  Fit weibull = fit_threshold(answers, 0.05, FitModel::weibull);
  EXPECT_TRUE(weibull.converged);
  EXPECT_NEAR(weibull.threshold, 1.0, 0.05);  // a different shape, but the same median region
  EXPECT_NEAR(fit_cdf(logistic, logistic.threshold), 0.5, 1e-9);
  EXPECT_NEAR(fit_cdf(weibull, weibull.threshold), 0.5, 1e-9);
}

}  // namespace
}  // namespace countershade::analysis
