#pragma once
// A simulated forced-choice observer with a known psychometric function, so pilots and tests can
// run the app without a person: it answers correctly with probability
// ψ(λ) = γ + (1 − γ)·(1 − exp(−(λ/α)^β)) (a Weibull, γ = 1/n), from its own seeded stream, a fixed
// delay after the answer is allowed.

#include <cstdint>
#include <functional>
#include <string>

namespace countershade::forced_choice {

struct ChoiceObserver {
  double alpha = 0.3, beta = 3;
  uint64_t seed = 1;
  double delay_s = 0.25;
  // P(correct) of a condition at λ with n alternatives, when set: the image-computable observer's
  // (--observer model:SEED, observer/model_observer.h) in place of the Weibull in λ.
  std::function<double(int condition, double lambda, int n_afc)> model;

  double probability_correct(double lambda, int n_afc, int condition = 0) const;
  // The answer to real trial `number` (practice: 0 and `practice_index`) of `condition` whose
  // target is `target`.
  int respond(int number, int practice_index, double lambda, int target, int n_afc,
              int condition = 0) const;
};

// Parses "weibull:ALPHA,BETA,SEED" (e.g. weibull:0.3,3,7); throws InputError naming --observer.
ChoiceObserver parse_choice_observer(const std::string& spec);

}  // namespace countershade::forced_choice
