#include "analysis/forced_choice_simulation.h"

#include <cmath>

#include "analysis/psychometric_solver.h"
#include "core/random.h"

namespace countershade::analysis {
namespace {

// A standard normal deviate from two uniforms (Box–Muller).
double normal(SampleStream& random) {
  const double u = 1 - random.next(), v = random.next();
  return std::sqrt(-2 * std::log(u)) * std::cos(2 * M_PI * v);
}

}  // namespace

double true_threshold(ThresholdModel model, double alpha, double beta) {
  return alpha * std::exp(inverse_base(model, 0.5) / beta);
}

std::vector<ForcedChoiceTrial> simulate_forced_choice(const ForcedChoiceDesign& d) {
  std::vector<ForcedChoiceTrial> trials;
  const double guess = 1.0 / d.n_afc;
  for (int s = 0; s < d.subjects; ++s) {
    char name[16];
    std::snprintf(name, sizeof name, "S%03d", s + 1);
    for (size_t c = 0; c < d.conditions.size(); ++c) {
      const SimulatedCondition& condition = d.conditions[c];
      SampleStream random(d.seed, 7, uint64_t(s), c);
      const double alpha = condition.alpha * std::exp(d.subject_sd * normal(random));
      for (double lambda : condition.levels) {
        const double F = base_value(d.model, condition.beta * std::log(lambda / alpha)).F;
        const double psi = guess + (1 - guess - d.lapse) * F;
        for (int r = 0; r < d.trials_per_level; ++r)
          trials.push_back({name, condition.scene, d.method, condition.sigma, lambda,
                            random.next() < psi, d.n_afc, false, "", 0});
      }
    }
  }
  return trials;
}

}  // namespace countershade::analysis
