#include "observer/model_observer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "observer/luminance_image.h"
#include "observer/set_prediction.h"

namespace countershade::observer {
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

nlohmann::json model_json(const std::vector<PredictedCondition>& conditions) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& c : conditions) {
    nlohmann::json at = nlohmann::json::array();
    for (double l : c.lambda_at)
      at.push_back(std::isinf(l) ? nlohmann::json(nullptr) : nlohmann::json(l));
    out.push_back({{"lambda_at", at}, {"lambda", c.lambda}, {"jnd", c.jnd}});
  }
  return out;
}

}  // namespace countershade::observer
