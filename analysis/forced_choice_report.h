#pragma once
// The forced-choice part of `analyze` as a page of its own (forced-choice.html): the fits of every
// condition, pooled and per subject, the psychometric figures, and the procedures' own estimates
// (QUEST+'s posteriors) beside the fits.

#include <nlohmann/json.hpp>
#include <string>

namespace countershade::analysis {

// `block`: results.json's forced_choice block (forced_choice_json, with its figures and
// procedure_estimates when there are any).
std::string forced_choice_report_html(const nlohmann::ordered_json& block);

}  // namespace countershade::analysis
