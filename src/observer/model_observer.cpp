#include "observer/model_observer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "observer/luminance_image.h"
#include "observer/set_prediction.h"

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

std::vector<PredictedCondition> predict_conditions(const std::filesystem::path& manifest,
                                                   const std::vector<ConditionName>& conditions,
                                                   const ModelObserverSpec& spec,
                                                   std::optional<double> set_ppd) {
  PredictionSettings settings;
  settings.ppd = spec.ppd.value_or(set_ppd.value_or(0));
  if (settings.ppd <= 0)
    throw_input_error("--observer",
                      "the set records no screen, so the model observer needs its pixels per "
                      "degree: model:SEED:PPD (e.g. model:1:36)");
  settings.display = srgb_display(100);
  const SetPrediction prediction =
      predict_set(read_manifest(manifest), manifest.parent_path(), settings);
  std::vector<PredictedCondition> out;
  for (const auto& c : conditions) {
    const auto found = std::find_if(
        prediction.conditions.begin(), prediction.conditions.end(), [&](const auto& p) {
          return p.scene == c.scene && p.method == c.method && std::abs(p.sigma - c.sigma) < 1e-9;
        });
    if (found == prediction.conditions.end())
      throw_input_error("--observer", "the model observer sees still images only; " + c.scene +
                                          " " + c.method + " is a sequence");
    PredictedCondition p{found->lambda, found->jnd, {}};
    for (size_t l = 0; l < p.lambda_at.size(); ++l)
      p.lambda_at[l] = found->lambda_at[l].value_or(std::numeric_limits<double>::infinity());
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

}  // namespace countershade::observer
