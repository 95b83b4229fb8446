#pragma once
// The comparison a forced-choice check exists for (docs/forced-choice.md, "Adjustment against
// forced choice"): per condition, each subject's λ_Low from the method of adjustment beside the
// same subject's forced-choice threshold, with a paired t-test on their log ratio across the
// subjects who have both.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "analysis/analysis.h"
#include "analysis/forced_choice_analysis.h"

namespace countershade::analysis {

struct MethodComparison {
  std::string scene, method;
  double sigma = 0;
  std::vector<std::string> subjects;  // those with both measures
  std::vector<std::string>
      without_threshold;  // with both, but a forced-choice fit with no finite maximum
  std::vector<double> lambda_low, threshold;  // per subject
  double geometric_mean_low = 0, geometric_mean_threshold = 0;
  double mean_log_ratio = 0;    // mean of ln(λ_Low / threshold)
  double t = 0, df = 0, p = 0;  // NaN with fewer than two subjects
};

std::vector<MethodComparison> compare_methods(const std::vector<BlockResults>& adjustment,
                                              const ForcedChoiceResults& forced_choice);
nlohmann::ordered_json comparison_json(const std::vector<MethodComparison>& rows);
std::string comparison_csv(const std::vector<MethodComparison>& rows);

}  // namespace countershade::analysis
