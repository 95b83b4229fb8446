#pragma once
// The forced-choice part of `analyze` (docs/forced-choice.md, "Fits"): a psychometric fit per
// condition pooled over subjects and per subject × condition, with bootstrap CIs and goodness of
// fit, as psychometric_fits.csv, a results.json block and one figure per scene.

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "analysis/forced_choice_trials.h"
#include "analysis/psychometric_fit.h"

namespace countershade::analysis {

struct ForcedChoiceOptions {
  ThresholdModel model = ThresholdModel::weibull;
  bool free_lapse = false;
  int bootstrap = 1000;
  uint64_t seed = 1;
};

struct PsychometricRow {
  bool pooled = true;
  std::string subject;  // "" when pooled
  std::string scene, label;
  double sigma = 0;
  std::vector<BinomialCell> cells;
  PsychometricFit fit;
};

struct ForcedChoiceResults {
  ForcedChoiceOptions options;
  std::vector<PsychometricRow> rows;  // per condition: the pooled row, then its subjects
  size_t trials = 0, browser_trials = 0;
  std::vector<std::string> warnings;
};

// Fits every condition; the bootstrap of each fit is seeded by `seed` and the row's key, so the
// numbers do not depend on the thread count.
ForcedChoiceResults analyze_forced_choice(const std::vector<ForcedChoiceTrial>& trials,
                                          const ForcedChoiceOptions& options);

// The results.json block.
nlohmann::ordered_json forced_choice_json(const ForcedChoiceResults& results);
// psychometric_fits.csv (docs/data-formats.md).
std::string psychometric_fits_csv(const ForcedChoiceResults& results);
// Proportion correct against λ with binomial 95 % intervals and the fitted curves, one figure per
// scene: scene → SVG.
std::vector<std::pair<std::string, std::string>> psychometric_figures(
    const ForcedChoiceResults& results);

}  // namespace countershade::analysis
