#pragma once
// A forced-choice session's trials as a plain state machine (docs/forced-choice.md): practice
// trials first, then one procedure per condition, interleaved in a seeded random order, each
// trial's target position balanced within blocks of n. It knows no window and no file: the
// session shows what current() says and feeds answer(); a resume replays the recorded answers
// through the same calls, so the procedures' state equals that of an uninterrupted run.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
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

// Why the procedures of a session of `config` would not fit in `limit` bytes, if they would not:
// the sum of ProcedureSettings::memory over its conditions, each on its own λ grid, with every
// shared part counted once. A session starts them all at once; the browser's export checks its
// engine's memory with it.
std::optional<std::string> procedure_memory_problem(const runtime::Study& study,
                                                    const ChoiceConfig& config, double limit);

class ChoiceRun {
 public:
  ChoiceRun(const runtime::Study& study, const ChoiceConfig& config, uint64_t seed);
  ChoiceRun(const ChoiceRun&) = delete;
  ChoiceRun& operator=(const ChoiceRun&) = delete;

  // The trial to show now; none when the session is finished. After an answer it is planned when
  // first asked for, and waits for its procedure's choice if that is still under way.
  const std::optional<ChoiceTrial>& current() const;
  // Whether current() answers at once (the procedure of the next trial is ready).
  bool ready() const;
  // The answer to the current trial (a position or interval); returns whether it was correct.
  bool answer(int response);
  bool finished() const { return !in_practice() && !next_slot(); }
  int real_trials_done() const { return real_done_; }
  bool in_practice() const { return practice_done_ < config_.practice_trials; }
  const std::vector<int>& conditions() const { return conditions_; }
  nlohmann::ordered_json procedure_state(int condition) const;

 private:
  std::optional<ChoiceTrial> plan_next() const;
  // The procedure (by slot) of the next real trial: an open one drawn in the seeded order.
  std::optional<size_t> next_slot() const;
  ChoiceTrial practice_trial(int k) const;
  int slot_of(int condition) const;

  const runtime::Study& study_;
  const ChoiceConfig& config_;
  uint64_t seed_;
  std::vector<int> conditions_, practice_conditions_;
  std::vector<ChoiceGrid> grids_;  // per selected condition
  std::vector<std::unique_ptr<ConditionProcedure>> procedures_;
  int practice_done_ = 0, real_done_ = 0;
  mutable std::optional<ChoiceTrial> current_;
  mutable bool planned_ = false;  // current_ is the trial to show now
};

}  // namespace countershade::forced_choice
