#include "serve/session_plan.h"

#include <algorithm>

#include "forced_choice/choice_row.h"
#include "formats/responses.h"
#include "procedures/choice_block.h"
#include "runtime/study.h"
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

// The forced-choice session as the page's engine runs it (web_engine's ChoiceSession): the study
// rebuilt from the page, the block as written, the session's seed; practice trials are not
// recorded, so they are answered at once.
struct SessionPlan::Choice {
  Choice(const json& page, const std::string& subject, int session)
      : study(web_engine::study_from_page(page)),
        config(
            procedures::parse_choice_config(page.at("forced_choice"), "study.js", "forced_choice")),
        run(study, config,
            config.seed ? runtime::session_seed(*config.seed, subject, session)
                        : web_engine::page_session_seed(page, subject, session)) {
    while (run.in_practice()) run.answer(run.current()->target);
  }
  runtime::Study study;
  procedures::ChoiceConfig config;
  forced_choice::ChoiceRun run;
};

SessionPlan::~SessionPlan() = default;

SessionPlan::SessionPlan(const StudyFolder& folder, std::string subject, int session)
    : folder_(folder), subject_(std::move(subject)), session_(session) {
  for (size_t c = 0; c < folder.columns.size(); ++c) column_[folder.columns[c]] = int(c);
  if (folder.kind != StudyKind::adjustment) {
    choice_ = std::make_unique<Choice>(folder.page, subject_, session_);
    return;
  }
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
  return adjustment ? check_adjustment(fields) : check_choice(fields);
}

std::string SessionPlan::check_choice(const std::vector<std::string>& fields) const {
  const auto& trial = choice_->run.current();
  if (!trial) not_in_plan("a trial after the session's last one");
  const std::vector<std::string> row(fields.begin(),
                                     fields.begin() + long(forced_choice::choice_columns().size()));
  const std::string problem =
      forced_choice::choice_row_problem(row, *trial, choice_->study, choice_->config.n_afc);
  if (!problem.empty()) not_in_plan(problem);
  return field(fields, "trial");
}

bool SessionPlan::record(const std::vector<std::string>& fields) {
  ++rows_stored;
  if (!choice_) return false;
  if (field(fields, "interval_timing") != "mistimed")
    choice_->run.answer(std::stoi(field(fields, "response")));
  return choice_->run.finished();
}

}  // namespace countershade::serve
