// Recovery of a known threshold: 100 simulated 2AFC observers (8 levels × 40 trials, Weibull
// truth, no lapse). The 95 % bootstrap CI of the fit with γ = 1/2 holds the true threshold at
// least 90 times; a naive fit that ignores the guess rate (γ = 0) almost never does, so the test
// can tell a fit that models the task from one that does not.

#include <gtest/gtest.h>

#include "analysis/forced_choice_simulation.h"
#include "analysis/psychometric_fit.h"

namespace countershade::analysis {
namespace {

// One simulated observer's cells: Weibull α = 0.3, β = 3, 8 levels × 40 trials.
std::vector<BinomialCell> simulated_cells(uint64_t seed) {
  ForcedChoiceDesign design;
  design.conditions = {{"scene", 0.01, 0.3, 3.0, {0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4}}};
  design.subjects = 1;
  design.seed = seed;
  return aggregate_cells(simulate_forced_choice(design)).begin()->second.pooled;
}

int coverage(double guess, double truth) {
  int covered = 0;
  for (int study = 0; study < 100; ++study) {
    const auto cells = simulated_cells(uint64_t(1000 + study));
    PsychometricFit fit = fit_psychometric(cells, {ThresholdModel::weibull, guess, false});
    bootstrap_psychometric(fit, cells, 1000, uint64_t(study));
    covered += fit.ci_low <= truth && truth <= fit.ci_high;
  }
  return covered;
}

TEST(PsychometricRecovery, BootstrapIntervalsHoldTheTrueThreshold) {
  const double truth = true_threshold(ThresholdModel::weibull, 0.3, 3.0);
  const int with_guess = coverage(0.5, truth), naive = coverage(0.0, truth);
  EXPECT_GE(with_guess, 90);
  EXPECT_LT(naive, 50);
  std::printf("true threshold %.4f: covered by %d of 100 CIs with γ = 1/2, by %d ignoring γ\n",
              truth, with_guess, naive);
}

TEST(PsychometricRecovery, TheDevianceOfTheTrueModelIsNotRejected) {
  // Under the generating model the bootstrap p-value is roughly uniform: about 5 of 100 below 0.05.
  int rejected = 0;
  for (int study = 0; study < 100; ++study) {
    const auto cells = simulated_cells(uint64_t(5000 + study));
    PsychometricFit fit = fit_psychometric(cells, {ThresholdModel::weibull, 0.5, false});
    bootstrap_psychometric(fit, cells, 500, uint64_t(study));
    rejected += fit.p_deviance < 0.05;
  }
  EXPECT_LE(rejected, 12);
  EXPECT_GE(rejected, 1);
}

}  // namespace
}  // namespace countershade::analysis
