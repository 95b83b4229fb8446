#include "adjust/simulated_observer.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/random.h"

namespace countershade::adjust {

// From the study runtime (src/runtime).
using runtime::InputEvent;
using runtime::Study;
namespace {

// A normal deviate from two counter-based uniforms (Box–Muller).
double normal(SampleStream& s) {
  double u1 = std::max(s.next(), 1e-300), u2 = s.next();
  return std::sqrt(-2 * std::log(u1)) * std::cos(2 * M_PI * u2);
}

}  // namespace

uint64_t parse_observer_spec(const std::string& spec) {
  const std::string prefix = "simulated:";
  if (spec.rfind(prefix, 0) == 0) {
    std::string digits = spec.substr(prefix.size());
    if (!digits.empty() && digits.size() <= 15 &&
        std::all_of(digits.begin(), digits.end(), ::isdigit))
      return std::stoull(digits);
  }
  throw_input_error(
      "--observer",
      "'" + spec + "' is not an observer (expected simulated:SEED, e.g. simulated:1)");
}

SimulatedObserver::SimulatedObserver(uint64_t seed, const Study& study, double step_interval_s,
                                     PredictedLevels predicted)
    : seed_(seed), study_(study), predicted_(std::move(predicted)), interval_s_(step_interval_s) {}

double SimulatedObserver::latent_lambda(int condition, int repetition, Question question) const {
  const Condition& c = study_.conditions[size_t(condition)];
  const double top = study_.lambda(c.grid_size - 1);
  // The observer's thresholds for this condition (fixed over repetitions), plus answer noise.
  SampleStream person(seed_, hash_string(c.scene + "/" + c.method), uint64_t(c.sigma * 1e9), 0);
  const double sensitivity = std::exp(0.2 * normal(person));
  const double spread[2] = {std::exp(0.1 * normal(person)), std::exp(0.1 * normal(person))};
  SampleStream noise(seed_, hash_string(c.scene + "/" + c.method), uint64_t(c.sigma * 1e9),
                     uint64_t(repetition) * 8 + int(question) + 1);
  const double answer_noise = std::exp(0.05 * normal(noise));
  if (!predicted_.empty()) {
    // The prediction's levels in question order: low at 1 JND, high at 4, best at 2.
    const auto& at = predicted_[size_t(condition)];
    const double level[kQuestionCount] = {at[0], at[2] * spread[0], at[1] * spread[1]};
    return level[int(question)] * sensitivity * answer_noise;
  }
  const double low = 0.2 * top * sensitivity;
  const double ratio[kQuestionCount] = {1.0, 3.0 * spread[0], 1.6 * spread[1]};
  return low * ratio[int(question)] * answer_noise;
}

int SimulatedObserver::answer_index(int condition, int repetition, Question question) const {
  const Condition& c = study_.conditions[size_t(condition)];
  const double latent = latent_lambda(condition, repetition, question);
  for (int i = 0; i < c.grid_size; ++i)
    if (study_.lambda(i) >= latent - 1e-12) return i;
  return c.grid_size - 1;
}

std::vector<InputEvent> SimulatedObserver::act(const Procedure& p, double time_s) {
  if (time_s < next_action_s_ || p.done()) return {};
  next_action_s_ = time_s + interval_s_;
  Key key = Key::enter;
  if (p.phase() == Procedure::Phase::question) {
    const int target = answer_index(p.trial().condition, p.trial().repetition, p.question());
    if (p.lambda_index() < target)
      key = Key::right;
    else if (p.lambda_index() > target)
      key = Key::left;
  } else if (p.phase() == Procedure::Phase::paused) {
    key = Key::escape;
  }
  return {{time_s, InputEvent::Kind::press, key}, {time_s, InputEvent::Kind::release, key}};
}

}  // namespace countershade::adjust
