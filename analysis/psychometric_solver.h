#pragma once
// The numerical core of the psychometric fits (analysis/psychometric_fit.h): the base functions
// and their derivatives, the likelihood of binomial cells, the expected information, Fisher
// scoring with Newton polish for b0 and b1 at a given lapse, and the lapse's profile.

#include <Eigen/Core>
#include <vector>

#include "analysis/psychometric_cells.h"

namespace countershade::analysis {

// F⁻¹(p): the η where the base function reaches p (F⁻¹(1/2) is the threshold's η).
double inverse_base(ThresholdModel model, double p);

// Cells sorted by λ with equal λ merged; λ ≤ 0 or k outside [0, n] is an InputError.
std::vector<BinomialCell> merge_cells(std::vector<BinomialCell> cells);

// Cells sorted by λ, with x = ln λ.
struct CellData {
  explicit CellData(std::vector<BinomialCell> c);
  size_t size() const { return cells.size(); }
  std::vector<BinomialCell> cells;
  std::vector<double> x;
  double saturated_nll = 0;  // −ln L of the saturated model: deviance = 2·(−ln L − this)
};

// F(η), 1 − F(η) (computed without cancellation), F'(η) and F''(η).
struct BaseValue {
  double F, Fc, f, df;
};
BaseValue base_value(ThresholdModel model, double eta);

struct LikelihoodTerms {
  double deviance = 0, loglik_bernoulli = 0, log_binomial_coefficients = 0;
};
LikelihoodTerms likelihood_terms(const CellData& data, const PsychometricOptions& options,
                                 double b0, double b1, double lapse);

// The expected (Fisher) information of (b0, b1[, ℓ]), as R's summary.glm uses it.
Eigen::MatrixXd expected_information(const CellData& data, const PsychometricOptions& options,
                                     double b0, double b1, double lapse, bool with_lapse);

// The deviance of the best infinitely steep function: the levels below the step at γ, the level at
// the step at its own k/n (clipped to [γ, 1 − ℓ]), the levels above at 1 − ℓ, with ℓ = 0 or the
// best ℓ in [0, max_lapse]. A deviance above it means the likelihood has no finite maximiser.
struct StepLimit {
  double deviance = 0;
  double lambda = 0;  // where the step is: the λ of the level at the step
};
StepLimit step_limit(const CellData& data, const PsychometricOptions& options);

struct CoefficientStart {
  double intercept = 0, slope = 1;
};
// Weighted least squares of the empirical F⁻¹ on ln λ.
CoefficientStart starting_coefficients(const CellData& data, const PsychometricOptions& options);

struct LapseSolution {
  double intercept = 0, slope = 0, lapse = 0;
  double deviance = 0;
  int profile_minima = 1;
  bool converged = false;
};
// `tolerance`: the last step's size relative to the coefficients; the bootstrap's refits need less
// than the reported fit.
LapseSolution solve_fixed_lapse(const CellData& data, const PsychometricOptions& options,
                                CoefficientStart start, double lapse = 0, double tolerance = 1e-13);
LapseSolution solve_free_lapse(const CellData& data, const PsychometricOptions& options,
                               CoefficientStart start);

}  // namespace countershade::analysis
