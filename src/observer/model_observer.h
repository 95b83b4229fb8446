#pragma once
// What a model observer answers from (`--observer model:SEED` in adjust and choose,
// docs/observer.md, "Pilots with the model"): the image-computable observer's prediction for each
// condition of a study, made once from the set's images when the session starts.

#include <array>
#include <cstdint>
#include <filesystem>
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

// P(correct) of an n-alternative forced choice at a response of `jnd`: a Weibull
// γ + (1 − γ)(1 − exp(−(jnd/α)^β)), γ = 1/n, β = 3.5, and α such that 1 JND gives 84 % correct
// with two alternatives (the model's definition of 1 JND).
double model_probability_correct(double jnd, int n_afc);

}  // namespace countershade::observer
