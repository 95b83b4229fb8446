#include "forced_choice/choice_row.h"

#include <cstdio>
#include <utility>

#include "core/error.h"
#include "core/number_format.h"

namespace countershade::forced_choice {

const std::vector<std::string>& choice_columns() {
  static const std::vector<std::string> columns = {
      "subject",          "session",    "trial",   "scene",
      "method",           "sigma",      "lambda",  "lambda_index",
      "lambda_requested", "n_afc",      "layout",  "target",
      "response",         "correct",    "rt_ms",   "procedure",
      "condition_trial",  "set_sha256", "time_utc"};
  return columns;
}

std::vector<std::string> choice_row(const runtime::Study& study, const ChoiceConfig& config,
                                    const ChoiceRowContext& who, const ChoiceTrial& t, int response,
                                    bool correct, double rt_s, const std::string& time_utc) {
  const auto& c = study.conditions[size_t(t.condition)];
  char rt[32];
  std::snprintf(rt, sizeof rt, "%.1f", rt_s * 1000);
  return {who.subject,
          std::to_string(who.session),
          std::to_string(t.number),
          c.scene,
          c.method,
          format_value(c.sigma),
          format_value(t.lambda),
          std::to_string(t.lambda_index),
          format_value(round_to(t.intensity.requested, 9)),
          std::to_string(config.n_afc),
          layout_name(config.layout),
          std::to_string(t.target),
          std::to_string(response),
          correct ? "1" : "0",
          rt,
          config.procedure_of(c.scene, c.method, c.sigma).type,
          std::to_string(t.condition_trial),
          who.set_sha256,
          time_utc};
}

namespace {

// Why a recorded row is not the trial the session would show now, or "" when it is.
std::string choice_row_mismatch(const std::vector<std::string>& row, const ChoiceTrial& t,
                                const runtime::Study& study) {
  const auto& c = study.conditions[size_t(t.condition)];
  const std::vector<std::pair<size_t, std::string>> expected = {
      {kColumnTrial, std::to_string(t.number)},
      {kColumnScene, c.scene},
      {kColumnMethod, c.method},
      {kColumnSigma, format_value(c.sigma)},
      {kColumnLambdaIndex, std::to_string(t.lambda_index)},
      {kColumnTarget, std::to_string(t.target)}};
  for (const auto& [column, value] : expected)
    if (row[column] != value)
      return choice_columns()[column] + " is '" + row[column] +
             "' where this session's plan has '" + value + "'";
  return "";
}

bool is_choice_response(const std::string& text, int n_afc) {
  return text.size() == 1 && text[0] >= '0' && text[0] < '0' + n_afc;
}

}  // namespace

std::string choice_row_problem(const std::vector<std::string>& row, const ChoiceTrial& t,
                               const runtime::Study& study, int n_afc) {
  const std::string mismatch = choice_row_mismatch(row, t, study);
  if (!mismatch.empty()) return mismatch;
  if (!is_choice_response(row[kColumnResponse], n_afc))
    return "response: expected a position from 0 to " + std::to_string(n_afc - 1);
  return "";
}

void replay_choice_rows(ChoiceRun& run, const std::vector<std::vector<std::string>>& rows,
                        const runtime::Study& study, int n_afc,
                        const std::function<std::string(size_t)>& where) {
  while (run.in_practice()) run.answer(run.current()->target);
  for (size_t r = 0; r < rows.size(); ++r) {
    const auto& row = rows[r];
    if (row.size() != choice_columns().size())
      throw_input_error(where(r),
                        "expected " + std::to_string(choice_columns().size()) + " fields");
    if (run.finished()) throw_input_error(where(r), "a trial after the session's last one");
    const std::string problem = choice_row_problem(row, *run.current(), study, n_afc);
    if (!problem.empty()) throw_input_error(where(r), problem);
    run.answer(std::stoi(row[kColumnResponse]));
  }
}

}  // namespace countershade::forced_choice
