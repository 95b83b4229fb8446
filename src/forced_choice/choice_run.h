#pragma once
// A forced-choice session's trials as a plain state machine (docs/forced-choice.md): practice
// trials first, then one procedure per condition, interleaved in a seeded random order, each
// trial's target position balanced within blocks of n. It knows no window and no file: the
// session shows what current() says and feeds answer(); a resume replays the recorded answers
// through the same calls, so the procedures' state equals that of an uninterrupted run.

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "forced_choice/condition_procedure.h"
#include "procedures/choice_block.h"
#include "runtime/study.h"

namespace countershade::forced_choice {

struct ChoiceTrial {
  int number = 0;  // 1-based among the real trials; 0 for practice
  bool practice = false;
  int condition = 0;        // index into the study's conditions
  int condition_trial = 0;  // 1-based within the condition
  Intensity intensity;
  int lambda_index = 0;  // the set's grid index shown
  double lambda = 0;
  int target = 0;  // position (spatial) or interval (temporal) of the enhanced image, 0-based
};

class ChoiceRun {
 public:
  ChoiceRun(const runtime::Study& study, const ChoiceConfig& config, uint64_t seed);
  ChoiceRun(const ChoiceRun&) = delete;
  ChoiceRun& operator=(const ChoiceRun&) = delete;

  // The trial to show now; none when the session is finished.
  const std::optional<ChoiceTrial>& current() const { return current_; }
  // The answer to the current trial (a position or interval); returns whether it was correct.
  bool answer(int response);
  bool finished() const { return !current_.has_value(); }
  int real_trials_done() const { return real_done_; }
  bool in_practice() const { return current_ && current_->practice; }
  const std::vector<int>& conditions() const { return conditions_; }
  nlohmann::ordered_json procedure_state(int condition) const;

 private:
  std::optional<ChoiceTrial> plan_next() const;
  ChoiceTrial practice_trial(int k) const;
  int slot_of(int condition) const;

  const runtime::Study& study_;
  const ChoiceConfig& config_;
  uint64_t seed_;
  std::vector<int> conditions_, practice_conditions_;
  std::vector<ChoiceGrid> grids_;  // per selected condition
  std::vector<std::unique_ptr<ConditionProcedure>> procedures_;
  int practice_done_ = 0, real_done_ = 0;
  std::optional<ChoiceTrial> current_;
};

}  // namespace countershade::forced_choice
