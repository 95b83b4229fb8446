#pragma once
// Psychometric functions of forced-choice data (docs/forced-choice.md, "Fits"):
// ψ(λ) = γ + (1 − γ − ℓ)·F(b0 + b1·ln λ), with F the Weibull (complementary log-log),
// log-logistic (logit) or log-normal (probit) base, the guess rate γ = 1/n fixed and the lapse ℓ
// either 0 or free in [0, 0.1] (Wichmann & Hill 2001). Maximum likelihood on binomial cells, with
// the standard errors of R's glm (expected information), the deviance and AIC as R reports them,
// the best infinitely steep function for detecting separation, and a seeded parametric bootstrap.

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "analysis/psychometric_cells.h"

namespace countershade::analysis {

struct PsychometricFit {
  PsychometricOptions options;
  double intercept = 0, slope = 0, lapse = 0;  // b0, b1 (η = b0 + b1·ln λ), ℓ
  double se_intercept = 0, se_slope = 0;
  double threshold = 0;      // λ where F = 1/2, so ψ = γ + (1 − γ − ℓ)/2
  double threshold_se = 0;   // delta method on ln threshold, times the threshold
  double threshold_psi = 0;  // λ where ψ = γ + (1 − γ)/2 (equals `threshold` when ℓ = 0)
  double deviance = 0, loglik_binomial = 0, loglik_bernoulli = 0, aic = 0;
  int df = 0;  // cells − parameters
  double deviance_step_limit = std::numeric_limits<double>::infinity();
  int profile_minima = 1;  // local minima of the deviance profile over ℓ (free lapse)
  bool lapse_at_bound = false;
  size_t n_cells = 0;
  long long n_trials = 0;
  bool converged = false;     // the estimates reached a finite fixed point
  bool well_defined = false;  // converged, and the likelihood has a finite maximiser
  // Parametric bootstrap (bootstrap_psychometric): 95 % percentile CI of the threshold and the
  // p-value of the deviance; NaN until run.
  double ci_low = std::numeric_limits<double>::quiet_NaN(),
         ci_high = std::numeric_limits<double>::quiet_NaN();
  double p_deviance = std::numeric_limits<double>::quiet_NaN();
  int bootstrap = 0;  // refits that converged
};

// Cells with the same λ are merged; λ must be > 0 and every n > 0.
PsychometricFit fit_psychometric(std::vector<BinomialCell> cells,
                                 const PsychometricOptions& options);

// ψ of a fit at λ.
double psychometric_probability(const PsychometricFit& fit, double lambda);

// Draws `resamples` data sets from the fit (same λ and n per cell), refits each and sets the
// threshold's CI and the deviance's p-value, (1 + #{D* ≥ D}) / (B + 1). Seeded per fit: the same
// seed and key give the same numbers whatever the thread count.
void bootstrap_psychometric(PsychometricFit& fit, const std::vector<BinomialCell>& cells,
                            int resamples, uint64_t seed);

}  // namespace countershade::analysis
