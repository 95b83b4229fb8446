#pragma once
// What a model observer answers from (`--observer model:SEED` in adjust and choose,
// docs/observer.md, "Pilots with the model"): the image-computable observer's prediction for each
// condition of a study, made once from the set's images when the session starts.

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "observer/model_response.h"

namespace countershade::observer {

struct ConditionName {
  std::string scene, method;
  double sigma = 0;
};

// The prediction for each of `conditions`, in order, from the set's images, seen at the spec's
// pixels per degree or else the set's (`set_ppd`) on an sRGB display with white at 100 cd/m².
// Throws InputError naming --observer when neither gives pixels per degree, or a condition has
// no still images in the set.
std::vector<PredictedCondition> predict_conditions(const std::filesystem::path& manifest,
                                                   const std::vector<ConditionName>& conditions,
                                                   const ModelObserverSpec& spec,
                                                   std::optional<double> set_ppd);

// The prediction as the exported page carries it (study.js "model", one entry per condition):
// {"lambda_at": [λ at 1, 2, 4 JND, null beyond the grid], "lambda": [...], "jnd": [...]}.
nlohmann::json model_json(const std::vector<PredictedCondition>& conditions);

}  // namespace countershade::observer
