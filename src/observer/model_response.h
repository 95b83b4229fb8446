#pragma once
// How a model observer answers from a prediction (docs/observer.md, "Pilots with the model"): the
// response at any λ of a condition, and P(correct) of a forced choice at a response. Plain
// arithmetic on the prediction's numbers, so that the exported page's WebAssembly runs it too.

#include <array>
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace countershade::observer {

// "model:SEED", or "model:SEED:PPD" where the set records no screen.
struct ModelObserverSpec {
  uint64_t seed = 0;
  std::optional<double> ppd;
};

// The spec when `spec` names a model observer ("model:…"), none when it names another kind;
// throws InputError naming --observer when it starts "model:" but is malformed.
std::optional<ModelObserverSpec> parse_model_observer(const std::string& spec);

// One condition's predicted response against λ over its grid.
struct PredictedCondition {
  std::vector<double> lambda, jnd;    // ascending λ
  std::array<double, 3> lambda_at{};  // λ at 1, 2 and 4 JND; +∞ where the grid ends below it
  // The response at λ: linear between grid values, the end values beyond them.
  double jnd_at(double lambda) const;
};

// The conditions of a page's "model" (observer/model_observer.h, model_json). Throws nlohmann's
// errors on a missing or mistyped field.
std::vector<PredictedCondition> predicted_conditions_of(const nlohmann::json& model);

// P(correct) of an n-alternative forced choice at a response of `jnd`: a Weibull
// γ + (1 − γ)(1 − exp(−(jnd/α)^β)), γ = 1/n, β = 3.5, and α such that 1 JND gives 84 % correct
// with two alternatives (the model's definition of 1 JND).
double model_probability_correct(double jnd, int n_afc);

// P(correct) of condition c at λ with n alternatives, model_probability_correct of the
// condition's response there: what a forced-choice model observer answers with
// (forced_choice::ChoiceObserver::model).
std::function<double(int condition, double lambda, int n_afc)> probability_by_condition(
    std::vector<PredictedCondition> conditions);

}  // namespace countershade::observer
