#include "forced_choice/choice_observer.h"

#include <cmath>
#include <sstream>

#include "core/error.h"
#include "core/random.h"

namespace countershade::forced_choice {

double ChoiceObserver::probability_correct(double lambda, int n_afc, int condition) const {
  if (model) return model(condition, lambda, n_afc);
  const double guess = 1.0 / n_afc;
  return guess + (1 - guess) * (1 - std::exp(-std::pow(lambda / alpha, beta)));
}

int ChoiceObserver::respond(int number, int practice_index, double lambda, int target, int n_afc,
                            int condition) const {
  SampleStream random(seed, 401, uint64_t(number), uint64_t(practice_index));
  if (random.next() < probability_correct(lambda, n_afc, condition)) return target;
  const int wrong = std::min(int(random.next() * (n_afc - 1)), n_afc - 2);  // one of the others
  return wrong >= target ? wrong + 1 : wrong;
}

ChoiceObserver parse_choice_observer(const std::string& spec) {
  const std::string prefix = "weibull:";
  ChoiceObserver o;
  if (spec.rfind(prefix, 0) == 0) {
    std::istringstream in(spec.substr(prefix.size()));
    char c1 = 0, c2 = 0;
    long long seed = -1;
    if (in >> o.alpha >> c1 >> o.beta >> c2 >> seed && c1 == ',' && c2 == ',' && in.peek() == EOF &&
        o.alpha > 0 && o.beta > 0 && std::isfinite(o.alpha) && std::isfinite(o.beta) && seed >= 0) {
      o.seed = uint64_t(seed);
      return o;
    }
  }
  throw_input_error(
      "--observer",
      "'" + spec + "' is not an observer (expected weibull:ALPHA,BETA,SEED, e.g. weibull:0.3,3,7)");
}

}  // namespace countershade::forced_choice
