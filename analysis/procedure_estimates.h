#pragma once
// The estimates a forced-choice procedure keeps itself (QUEST+'s posterior), recomputed from each
// session's trials for `analyze` and set beside the psychometric fit of the same subject and
// condition: procedure_estimates.csv (docs/data-formats.md) and results.json.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "analysis/forced_choice_analysis.h"

namespace countershade::analysis {

struct ProcedureEstimate {
  std::string subject;
  int session = 0;
  std::string scene, label;
  double sigma = 0;
  size_t trials = 0;
  nlohmann::ordered_json estimate;  // the procedure's summary: mode, mean, quantiles, …
};

// For each forced-choice file whose sidecar (the .json beside it) names a procedure that keeps a
// posterior: per condition, that procedure's estimate from the file's trials. A sidecar that
// cannot be read or names a procedure this program lacks adds a warning and no estimate.
std::vector<ProcedureEstimate> procedure_estimates(const std::vector<std::filesystem::path>& files,
                                                   std::vector<std::string>& warnings);

// One row per estimate and quantity (each parameter, and the λ where F = 1/2), the latter with the
// same subject × condition's psychometric fit beside it.
std::string procedure_estimates_csv(const std::vector<ProcedureEstimate>& estimates,
                                    const ForcedChoiceResults& fits);
nlohmann::ordered_json procedure_estimates_json(const std::vector<ProcedureEstimate>& estimates);

}  // namespace countershade::analysis
