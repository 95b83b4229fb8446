#pragma once
// What a psychometric fit is given (analysis/psychometric_fit.h): binomial cells and the options,
// shared by the fit and its solver.

#include "analysis/threshold_model.h"

namespace countershade::analysis {

// k correct answers out of n trials at one λ.
struct BinomialCell {
  double lambda = 0;
  long long k = 0, n = 0;
};

struct PsychometricOptions {
  ThresholdModel model = ThresholdModel::weibull;
  double guess = 0.5;       // γ = 1/n for n alternatives
  bool free_lapse = false;  // false: ℓ = 0
  double max_lapse = 0.1;
};

}  // namespace countershade::analysis
