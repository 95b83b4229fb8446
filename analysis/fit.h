#pragma once
// Threshold fits by maximum likelihood with interval censoring from the λ grid: an answer λ means
// the observer's threshold lies in (λ − step, λ]; an answer at the first grid step (or 0) is
// left-censored, (0, step]. Solved with Ceres (bounded), standard errors from the observed
// information (the exact Hessian of the log-likelihood, as R's survreg reports them), and a
// seeded parametric bootstrap for confidence intervals.

#include <cstdint>
#include <string>
#include <vector>

namespace countershade::analysis {

enum class FitModel { lognormal, weibull, logistic };
FitModel parse_fit_model(const std::string& name);  // throws InputError
const char* fit_model_name(FitModel model);

struct Fit {
  FitModel model = FitModel::lognormal;
  double location = 0, scale = 0;  // μ and σ of the model (log scale for lognormal and Weibull)
  double location_se = 0;
  double threshold = 0;      // the distribution's median, in λ units
  double log_threshold = 0;  // ln(threshold)
  double log_threshold_se = 0;
  size_t n = 0;
  bool converged = false;
  double ci_low = 0, ci_high = 0;  // bootstrap 95% CI of the threshold (when bootstrapped)
  int bootstrap = 0;
};

// Fits `answers` (raw λ values on a grid of `step`).
Fit fit_threshold(const std::vector<double>& answers, double step, FitModel model);

// The model's cumulative distribution function at λ.
double fit_cdf(const Fit& fit, double lambda);

// Adds percentile bootstrap CIs from B data sets simulated from `fit` and quantised to the grid.
void bootstrap_threshold(Fit& fit, double step, int resamples, uint64_t seed);

}  // namespace countershade::analysis
