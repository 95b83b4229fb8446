#pragma once
// The prediction an exported page carries for its model observers (study.js "model", written by
// export-web --model-ppd), as the page's engine reads it (and the native tests that check it).

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/error.h"
#include "forced_choice/choice_observer.h"
#include "observer/model_response.h"

namespace countershade::web_engine {

// The page's prediction per condition, for `model` (model:SEED: the page's prediction has its own
// pixels per degree). Throws InputError when the spec gives pixels per degree or the page has no
// prediction.
inline std::vector<observer::PredictedCondition> predicted_page_conditions(
    const nlohmann::json& page, const observer::ModelObserverSpec& model) {
  if (model.ppd)
    throw_input_error("observer", "the page's prediction has its pixels per degree: model:SEED");
  if (!page.contains("model"))
    throw_input_error("observer",
                      "the study was exported without a prediction (export-web --model-ppd)");
  return observer::predicted_conditions_of(page.at("model"));
}

// The page's forced-choice observer of a spec: weibull:ALPHA,BETA,SEED, or model:SEED answering
// from the page's prediction.
inline forced_choice::ChoiceObserver page_choice_observer(const nlohmann::json& page,
                                                          const std::string& spec) {
  const auto model = observer::parse_model_observer(spec);
  if (!model) return forced_choice::parse_choice_observer(spec);
  forced_choice::ChoiceObserver o;
  o.seed = model->seed;
  o.model = observer::probability_by_condition(predicted_page_conditions(page, *model));
  return o;
}

}  // namespace countershade::web_engine
