#include "observer/model_response.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <memory>

#include "core/error.h"

namespace countershade::observer {
namespace {

constexpr double kWeibullSlope = 3.5;  // a typical slope of contrast detection (Weibull β)

bool all_digits(const std::string& text) {
  return !text.empty() && text.size() <= 15 &&
         std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

}  // namespace

std::optional<ModelObserverSpec> parse_model_observer(const std::string& spec) {
  const std::string prefix = "model:";
  if (spec.rfind(prefix, 0) != 0) return std::nullopt;
  const std::string rest = spec.substr(prefix.size());
  const size_t colon = rest.find(':');
  const std::string seed = rest.substr(0, colon);
  ModelObserverSpec out;
  bool valid = all_digits(seed);
  if (valid) out.seed = std::stoull(seed);
  if (valid && colon != std::string::npos) {
    char* end = nullptr;
    const std::string ppd = rest.substr(colon + 1);
    const double value = std::strtod(ppd.c_str(), &end);
    valid = !ppd.empty() && end == ppd.c_str() + ppd.size() && value >= 1 && value <= 10000;
    out.ppd = value;
  }
  if (!valid)
    throw_input_error("--observer", "'" + spec +
                                        "' is not a model observer (expected model:SEED or "
                                        "model:SEED:PPD, PPD from 1 to 10000, e.g. model:1:36)");
  return out;
}

double PredictedCondition::jnd_at(double l) const {
  if (lambda.empty()) return 0;
  if (l <= lambda.front()) return jnd.front();
  if (l >= lambda.back()) return jnd.back();
  const size_t i = size_t(std::upper_bound(lambda.begin(), lambda.end(), l) - lambda.begin());
  const double t = (l - lambda[i - 1]) / (lambda[i] - lambda[i - 1]);
  return jnd[i - 1] + t * (jnd[i] - jnd[i - 1]);
}

std::vector<PredictedCondition> predicted_conditions_of(const nlohmann::json& model) {
  std::vector<PredictedCondition> out;
  for (const auto& c : model) {
    PredictedCondition p;
    p.lambda = c.at("lambda").get<std::vector<double>>();
    p.jnd = c.at("jnd").get<std::vector<double>>();
    for (size_t l = 0; l < p.lambda_at.size(); ++l) {
      const auto& v = c.at("lambda_at").at(l);
      p.lambda_at[l] = v.is_null() ? std::numeric_limits<double>::infinity() : v.get<double>();
    }
    out.push_back(std::move(p));
  }
  return out;
}

double model_probability_correct(double jnd, int n_afc) {
  // 2AFC: 0.5 + 0.5·(1 − exp(−(1/α)^β)) = 0.84  ⇒  (1/α)^β = −ln(0.32).
  static const double alpha = std::pow(-std::log(0.32), -1.0 / kWeibullSlope);
  const double guess = 1.0 / n_afc;
  return guess + (1 - guess) * (1 - std::exp(-std::pow(std::max(jnd, 0.0) / alpha, kWeibullSlope)));
}

std::function<double(int, double, int)> probability_by_condition(
    std::vector<PredictedCondition> conditions) {
  auto shared = std::make_shared<const std::vector<PredictedCondition>>(std::move(conditions));
  return [shared](int condition, double lambda, int n_afc) {
    return model_probability_correct((*shared)[size_t(condition)].jnd_at(lambda), n_afc);
  };
}

}  // namespace countershade::observer
