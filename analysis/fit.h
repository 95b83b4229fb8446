#pragma once
// Threshold fits by maximum likelihood with interval censoring from the λ grid (methods.md,
// threshold fits): an answer at grid index i means the observer's threshold lies in
// (λ_{i−1}, λ_i]; the first grid value is left-censored, (0, λ_i]; an answer at the top of the
// grid is right-censored, (λ_{i−1}, ∞). Solved with Ceres (bounded), standard errors from the
// observed information (the exact Hessian of the log-likelihood, as R's survreg reports them),
// and a seeded parametric bootstrap for confidence intervals.

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "analysis/threshold_model.h"

namespace countershade::analysis {

// Where an answer puts the threshold: (lower, upper]. lower = 0 is left-censored, upper = ∞
// right-censored.
struct AnswerInterval {
  double lower = 0, upper = 0;
  bool operator<(const AnswerInterval& o) const {
    return lower < o.lower || (lower == o.lower && upper < o.upper);
  }
};

// The λ grid an answer was given on: λ_i = first + i·step, and the top the observer could reach
// (∞ when unknown: nothing is right-censored).
struct AnswerGrid {
  double first = 0, step = 0;
  double top = std::numeric_limits<double>::infinity();
};

// The interval of an answer λ at grid index `index` (−1: unknown, then λ_{i−1} = λ − step) on a
// grid with the given step and top (0: unknown). An answer of λ = 0 counts as (0, λ_1] and sets
// *zero when given.
AnswerInterval answer_interval(double lambda, int index, double step, double top,
                               bool* zero = nullptr);

struct Fit {
  ThresholdModel model = ThresholdModel::log_normal;
  double location = 0, scale = 0;  // μ and σ of the model (log scale for lognormal and Weibull)
  double location_se = 0;
  double threshold = 0;      // the distribution's median, in λ units
  double log_threshold = 0;  // ln(threshold)
  double log_threshold_se = 0;
  size_t n = 0;
  size_t left_censored = 0, right_censored = 0;  // answers at the bottom and the top of the grid
  // false when every answer is censored on the same side, or when every answer lies in one grid
  // step or on the two sides of one step boundary (`one_step`: no spread to fit, the threshold
  // is that boundary). An unidentified fit has no standard errors (NaN).
  bool identified = true;
  bool one_step = false;
  bool converged = false;  // never true for an unidentified fit
  // Bootstrap 95% CI of the threshold; NaN (NA, null) unless at least two refits converged.
  double ci_low = std::numeric_limits<double>::quiet_NaN(),
         ci_high = std::numeric_limits<double>::quiet_NaN();
  int bootstrap = 0;
};

Fit fit_threshold(const std::vector<AnswerInterval>& answers, ThresholdModel model);

// The model's cumulative distribution function at λ.
double fit_cdf(const Fit& fit, double lambda);

// Adds percentile bootstrap CIs from B data sets simulated from `fit` and answered on `grid`
// (the first grid value at or above each simulated threshold, at most the top).
void bootstrap_threshold(Fit& fit, const AnswerGrid& grid, int resamples, uint64_t seed);

}  // namespace countershade::analysis
