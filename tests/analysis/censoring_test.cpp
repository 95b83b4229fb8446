// The censoring rules of the threshold fits (methods.md, threshold fits): intervals from each
// answer's own grid, left-censoring at the first value, right-censoring at the top, and the
// standard error of the reported threshold.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "analysis/analysis.h"
#include "analysis/fit.h"
#include "analysis/simulate.h"

namespace countershade::analysis {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

TEST(Censoring, IntervalsComeFromTheAnswersOwnGrid) {
  // A grid from 0.25 in steps of 0.05 up to 1: index 0 is the first value, left-censored.
  AnswerInterval first = answer_interval(0.25, 0, 0.05, 1.0);
  EXPECT_EQ(first.lower, 0.0);
  EXPECT_DOUBLE_EQ(first.upper, 0.25);
  AnswerInterval second = answer_interval(0.30, 1, 0.05, 1.0);
  EXPECT_DOUBLE_EQ(second.lower, 0.25);
  EXPECT_DOUBLE_EQ(second.upper, 0.30);
  AnswerInterval top = answer_interval(1.0, 15, 0.05, 1.0);
  EXPECT_DOUBLE_EQ(top.lower, 0.95);
  EXPECT_EQ(top.upper, kInfinity);
  // Without a top nothing is right-censored; without an index, only λ ≤ step is left-censored.
  EXPECT_DOUBLE_EQ(answer_interval(1.0, 15, 0.05, 0.0).upper, 1.0);
  EXPECT_DOUBLE_EQ(answer_interval(0.25, -1, 0.05, 0.0).lower, 0.20);
  EXPECT_EQ(answer_interval(0.05, -1, 0.05, 0.0).lower, 0.0);
  // λ = 0 (a grid that starts at 0) counts as (0, λ_1].
  bool zero = false;
  AnswerInterval at_zero = answer_interval(0.0, 0, 0.05, 3.0, &zero);
  EXPECT_TRUE(zero);
  EXPECT_EQ(at_zero.lower, 0.0);
  EXPECT_DOUBLE_EQ(at_zero.upper, 0.05);
}

// The standard normal quantile, by bisection of the CDF.
double normal_quantile(double u) {
  double lo = -8, hi = 8;
  for (int k = 0; k < 100; ++k) {
    const double mid = 0.5 * (lo + hi);
    (0.5 * std::erfc(-mid / std::numbers::sqrt2) < u ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// Expected answers of a log-normal population (median 0.4, SD of ln λ 0.45) on a grid that
// starts at 0.25: the first value holds everything below it. The fit recovers the population;
// reading the first answer as (0.20, 0.25] would not.
TEST(Censoring, AGridStartingAtAQuarterIsFittedWithItsOwnFirstValue) {
  const double step = 0.05, first = 0.25, median = 0.4, sd = 0.45;
  std::vector<AnswerInterval> answers, misread;
  for (int i = 0; i < 400; ++i) {
    const double u = (i + 0.5) / 400.0;
    const double t = median * std::exp(sd * normal_quantile(u));
    const int index = std::max(0, int(std::ceil((t - first) / step - 1e-9)));
    const double lambda = first + index * step;
    answers.push_back(answer_interval(lambda, index, step, 0.0));
    misread.push_back(answer_interval(lambda, -1, step, 0.0));
  }
  const Fit fit = fit_threshold(answers, ThresholdModel::log_normal);
  EXPECT_TRUE(fit.converged);
  EXPECT_GT(fit.left_censored, 40u);
  EXPECT_NEAR(fit.threshold, median, 0.01);
  EXPECT_NEAR(fit.scale, sd, 0.02);
  const Fit wrong = fit_threshold(misread, ThresholdModel::log_normal);
  EXPECT_GT(std::abs(wrong.scale - sd), 0.03)
      << "the misread grid should distort the fit: " << wrong.scale;
}

// The logistic is left-censored with F(λ_1), not F(λ_1) − F(0): a population with mass below 0
// (μ = 0.12, s = 0.1 on the λ scale) is recovered from its expected answers.
TEST(Censoring, LogisticFirstStepIsLeftCensored) {
  const double step = 0.05, mu = 0.12, s = 0.1;
  std::vector<AnswerInterval> answers;
  for (int i = 0; i < 400; ++i) {
    const double u = (i + 0.5) / 400.0, t = mu + s * std::log(u / (1 - u));
    const int index = std::max(0, int(std::ceil(t / step - 1e-9)) - 1);  // grid from 0.05
    answers.push_back(answer_interval(step * (index + 1), index, step, 0.0));
  }
  const Fit fit = fit_threshold(answers, ThresholdModel::logistic);
  EXPECT_TRUE(fit.converged);
  EXPECT_NEAR(fit.location, mu, 0.01);
  EXPECT_NEAR(fit.scale, s, 0.01);
}

TEST(Censoring, AllAnswersAtTheFirstStepAreUnidentified) {
  const std::vector<AnswerInterval> answers(12, answer_interval(0.05, 0, 0.05, 3.0));
  for (ThresholdModel model :
       {ThresholdModel::logistic, ThresholdModel::log_normal, ThresholdModel::weibull}) {
    const Fit fit = fit_threshold(answers, model);
    EXPECT_FALSE(fit.identified) << threshold_model_name(model);
    EXPECT_FALSE(fit.converged) << threshold_model_name(model);
    EXPECT_EQ(fit.left_censored, 12u);
    EXPECT_EQ(fit.right_censored, 0u);
  }
  const std::vector<AnswerInterval> top(12, answer_interval(3.0, 60, 0.05, 3.0));
  const Fit fit = fit_threshold(top, ThresholdModel::log_normal);
  EXPECT_FALSE(fit.identified);
  EXPECT_EQ(fit.right_censored, 12u);
}

// −ln L of interval answers under the Weibull (minimum extreme value on ln λ), written out
// independently of the fit's code.
double weibull_nll(const std::vector<AnswerInterval>& answers, double mu, double log_sigma) {
  auto F = [&](double lambda) {
    if (lambda <= 0) return 0.0;
    if (std::isinf(lambda)) return 1.0;
    return 1.0 - std::exp(-std::exp((std::log(lambda) - mu) / std::exp(log_sigma)));
  };
  double nll = 0;
  for (const auto& a : answers) nll -= std::log(F(a.upper) - F(a.lower));
  return nll;
}

// The Weibull's log-threshold is the log-median μ + σ ln ln 2; its SE by the delta method must
// equal √(gᵀ H⁻¹ g) with the Hessian H and the gradient g taken by finite differences here.
TEST(Censoring, WeibullLogMedianStandardErrorByTheDeltaMethod) {
  std::vector<AnswerInterval> answers;
  for (int i = 0; i < 60; ++i) {
    const double u = (i + 0.5) / 60.0, t = std::exp(0.2 + 0.35 * std::log(-std::log(1 - u)));
    const int index = std::max(0, int(std::ceil(t / 0.1 - 1e-9)) - 1);
    answers.push_back(answer_interval(0.1 * (index + 1), index, 0.1, 2.0));
  }
  const Fit fit = fit_threshold(answers, ThresholdModel::weibull);
  ASSERT_TRUE(fit.converged);
  EXPECT_GT(fit.right_censored, 0u);
  const double q[2] = {fit.location, std::log(fit.scale)}, e = 1e-4;
  double h[2][2];
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) {
      auto at = [&](double da, double db) {
        double p[2] = {q[0], q[1]};
        p[a] += da;
        p[b] += db;
        return weibull_nll(answers, p[0], p[1]);
      };
      h[a][b] = (at(e, e) - at(e, -e) - at(-e, e) + at(-e, -e)) / (4 * e * e);
    }
  auto log_median = [](double mu, double log_sigma) {
    return mu + std::exp(log_sigma) * std::log(std::log(2.0));
  };
  const double g[2] = {(log_median(q[0] + e, q[1]) - log_median(q[0] - e, q[1])) / (2 * e),
                       (log_median(q[0], q[1] + e) - log_median(q[0], q[1] - e)) / (2 * e)};
  const double det = h[0][0] * h[1][1] - h[0][1] * h[1][0];
  const double inv[2][2] = {{h[1][1] / det, -h[0][1] / det}, {-h[1][0] / det, h[0][0] / det}};
  double variance = 0;
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) variance += g[a] * inv[a][b] * g[b];
  EXPECT_NEAR(fit.log_threshold, log_median(q[0], q[1]), 1e-12);
  EXPECT_NEAR(fit.log_threshold_se, std::sqrt(variance), 1e-3 * std::sqrt(variance));
  EXPECT_GT(std::abs(fit.log_threshold_se - fit.location_se), 0.01 * fit.location_se)
      << "the log-median's SE differs from μ's";
}

// Answers in one step, or split by one step boundary, are fitted best by a spread shrinking to 0
// at that boundary: no spread and no standard error, the boundary as the threshold. Three steps
// pin the spread down.
TEST(Censoring, AnswersAtOneStepBoundaryHaveNoSpread) {
  const AnswerInterval a{0.25, 0.30}, b{0.30, 0.35}, c{0.35, 0.40};
  for (const auto& answers :
       {std::vector<AnswerInterval>{a, a, a, a}, std::vector<AnswerInterval>{a, a, b, a, b}}) {
    const Fit fit = fit_threshold(answers, ThresholdModel::log_normal);
    EXPECT_FALSE(fit.identified);
    EXPECT_TRUE(fit.one_step);
    EXPECT_FALSE(fit.converged);
    EXPECT_DOUBLE_EQ(fit.threshold, 0.30);
    EXPECT_TRUE(std::isnan(fit.log_threshold_se));
  }
  const Fit spread = fit_threshold({a, b, b, c, b}, ThresholdModel::log_normal);
  EXPECT_TRUE(spread.identified);
  EXPECT_TRUE(spread.converged);
  EXPECT_LT(spread.log_threshold_se, 0.1);
}

}  // namespace
}  // namespace countershade::analysis
