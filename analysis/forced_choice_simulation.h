#pragma once
// Simulated forced-choice observers with a known psychometric function, for pilots, tests and
// benchmarks: each trial's answer is drawn from ψ(λ) = γ + (1 − γ − ℓ)·F(β·ln(λ/α)) with F the
// model's base (Weibull: the threshold where F = 1/2 is α·(ln 2)^(1/β)).

#include <cstdint>
#include <string>
#include <vector>

#include "analysis/forced_choice_trials.h"

namespace countershade::analysis {

struct SimulatedCondition {
  std::string scene = "scene";
  double sigma = 0.01;
  double alpha = 0.3, beta = 3;  // the group's psychometric function: η = β·ln(λ/α)
  std::vector<double> levels;    // the λ of the method of constant stimuli
};

struct ForcedChoiceDesign {
  std::vector<SimulatedCondition> conditions;
  int subjects = 4;
  int trials_per_level = 40;
  int n_afc = 2;
  double lapse = 0;
  double subject_sd = 0;  // SD of ln α over subjects
  ThresholdModel model = ThresholdModel::weibull;
  uint64_t seed = 1;
  std::string method;  // the trials' label (the app writes the condition's method)
};

// Trials in a fixed order (subject S001…, condition, level, repetition); the same design gives
// the same answers.
std::vector<ForcedChoiceTrial> simulate_forced_choice(const ForcedChoiceDesign& design);

// The λ where the base function is 1/2: the threshold a fit should recover.
double true_threshold(ThresholdModel model, double alpha, double beta);

}  // namespace countershade::analysis
