#pragma once
// One forced-choice trial as a row of the trials CSV (docs/data-formats.md, "Forced-choice
// trials"): the columns and their text, written alike by the app's recorder and by the browser's
// engine, so both give the same rows.

#include <functional>
#include <string>
#include <vector>

#include "forced_choice/choice_run.h"
#include "runtime/study.h"

namespace countershade::forced_choice {

// The CSV's columns, in order.
const std::vector<std::string>& choice_columns();

// Where each column a replay checks stands in a row (choice_columns()).
enum ChoiceColumn : size_t {
  kColumnTrial = 2,
  kColumnScene = 3,
  kColumnMethod = 4,
  kColumnSigma = 5,
  kColumnLambdaIndex = 7,
  kColumnTarget = 11,
  kColumnResponse = 12,
};

struct ChoiceRowContext {
  std::string subject;
  int session = 1;
  std::string set_sha256;
};

// The row of an answered trial; `time_utc` as the recorder stamps it (core/time.h).
std::vector<std::string> choice_row(const runtime::Study& study, const ChoiceConfig& config,
                                    const ChoiceRowContext& who, const ChoiceTrial& trial,
                                    int response, bool correct, double rt_s,
                                    const std::string& time_utc);

// Why a recorded row is not an answer to trial `t` (its trial, condition, λ index and target,
// and a response among the n positions), or "" when it is.
std::string choice_row_problem(const std::vector<std::string>& row, const ChoiceTrial& t,
                               const runtime::Study& study, int n_afc);

// Replays recorded rows (no header) into a fresh run, as a resume does: the practice trials are
// skipped (they are not recorded), and each row must be the trial the run shows next, with a
// response among the n positions. Throws InputError naming where(i) for row i.
void replay_choice_rows(ChoiceRun& run, const std::vector<std::vector<std::string>>& rows,
                        const runtime::Study& study, int n_afc,
                        const std::function<std::string(size_t)>& where);

}  // namespace countershade::forced_choice
