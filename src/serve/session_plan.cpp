#include "serve/session_plan.h"

#include <algorithm>

#include "formats/responses.h"
#include "serve/refusal.h"
#include "web_engine/page_study.h"

namespace countershade::serve {
namespace {

using nlohmann::json;

// An index into a list of `size` entries, written as the page writes it (decimal, no sign).
bool is_index_below(const std::string& text, size_t size) {
  if (text.empty() || text.size() > 9 || text.find_first_not_of("0123456789") != std::string::npos)
    return false;
  return std::stoul(text) < size;
}

[[noreturn]] void not_in_plan(const std::string& what) {
  throw Refusal(422, "not in the plan", "row: " + what);
}

}  // namespace

SessionPlan::SessionPlan(const StudyFolder& folder, std::string subject, int session)
    : folder_(folder), subject_(std::move(subject)), session_(session) {
  for (size_t c = 0; c < folder.columns.size(); ++c) column_[folder.columns[c]] = int(c);
  if (folder.kind != StudyKind::adjustment) return;
  for (const adjust::Trial& t : web_engine::page_plan(folder.page, subject_, session_)) {
    if (t.practice) continue;
    trials_[std::to_string(t.number)] = {t.condition, std::to_string(t.repetition),
                                         procedures::side_name(t.side)};
    answers_expected_ += kQuestionCount;
  }
}

const std::string& SessionPlan::field(const std::vector<std::string>& fields,
                                      const char* column) const {
  return fields[size_t(column_.at(column))];
}

// The scene, method and σ of the row are those of page condition `condition`.
void SessionPlan::check_condition(const std::vector<std::string>& fields, int condition) const {
  const json& c = folder_.page.at("conditions").at(size_t(condition));
  for (const char* column : {"scene", "method", "sigma"})
    if (field(fields, column) != c.at(column).get<std::string>())
      not_in_plan(std::string(column) + " is '" + field(fields, column) + "' where the plan has '" +
                  c.at(column).get<std::string>() + "'");
  const std::string& index = field(fields, "lambda_index");
  if (!is_index_below(index, c.at("grid").size()))
    not_in_plan("lambda_index '" + index + "' is not on the condition's grid");
}

std::string SessionPlan::check_adjustment(const std::vector<std::string>& fields) const {
  const auto trial = trials_.find(field(fields, "trial"));
  if (trial == trials_.end()) not_in_plan("trial '" + field(fields, "trial") + "' is not planned");
  const Expected& e = trial->second;
  check_condition(fields, e.condition);
  if (field(fields, "repetition") != e.repetition || field(fields, "side") != e.side)
    not_in_plan("repetition or side differs from the plan's trial " + trial->first);
  const std::string& question = field(fields, "question");
  if (!question_from_name(question)) not_in_plan("question '" + question + "' is none of three");
  const json& grid = folder_.page.at("conditions").at(size_t(e.condition)).at("grid");
  if (field(fields, "lambda") != grid.at(std::stoul(field(fields, "lambda_index"))))
    not_in_plan("lambda is not the grid's value at lambda_index");
  return trial->first + ":" + question;
}

std::string SessionPlan::check(const std::vector<std::string>& fields) const {
  const bool adjustment = folder_.kind == StudyKind::adjustment;
  if (field(fields, "subject") != subject_ || field(fields, "session") != std::to_string(session_))
    throw Refusal(403, "another participant's row", "row: not the token's subject and session");
  if (field(fields, adjustment ? "stimulus_set" : "set_sha256") != folder_.set_sha256)
    throw Refusal(403, "another study's row", "row: the stimulus set is not this study's");
  if (adjustment) return check_adjustment(fields);
  const auto& conditions = folder_.page.at("conditions");
  const auto match = std::find_if(conditions.begin(), conditions.end(), [&](const json& c) {
    return c.at("scene") == field(fields, "scene") && c.at("method") == field(fields, "method") &&
           c.at("sigma") == field(fields, "sigma");
  });
  if (match == conditions.end())
    not_in_plan("no condition of the study has this scene, method and σ");
  check_condition(fields, int(match - conditions.begin()));
  return "";
}

}  // namespace countershade::serve
