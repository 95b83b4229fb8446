#pragma once
// An up/down staircase with the rules of PsychoPy's StairHandler (docs/forced-choice.md): an
// nUp/nDown run counter, 1-up/1-down until the first reversal, a list of step sizes that advances
// at reversals, lin/log/dB steps clipped to [minVal, maxVal], and an end on trials and reversals.
// Intensities are in the procedure's own units; the app snaps them to the set's λ grid and
// records the λ it showed.

#include <optional>
#include <vector>

#include "core/parameters.h"

namespace countershade::procedures {

enum class StepType { lin, log, db };

struct StaircaseRules {
  double start = 0;
  std::vector<double> step_sizes = {4.0};
  StepType step_type = StepType::db;
  int n_up = 1, n_down = 3;
  int n_trials = 0;
  std::optional<int> n_reversals;  // at least the number of step sizes
  std::optional<double> min_value, max_value;
  bool apply_initial_rule = true;
};

// Reads StairHandler's arguments (startVal, stepSizes, stepType, nUp, nDown, nTrials,
// nReversals, minVal, maxVal, applyInitialRule) and checks them together.
StaircaseRules read_staircase_rules(const ParameterBag& bag);
// Their documentation, with the defaults read_staircase_rules uses.
std::vector<ParameterDoc> staircase_parameter_docs();

class Staircase {
 public:
  explicit Staircase(StaircaseRules rules);

  // The intensity of the next trial.
  double next_intensity() const { return next_; }
  // Records the answer to a trial shown at next_intensity(), or at `shown` where the display could
  // only show a nearby value (StairHandler's addResponse with an intensity): the shown value is
  // recorded, and the staircase steps on from its own. Returns whether it was a reversal.
  bool add_response(bool correct, std::optional<double> shown = std::nullopt);
  bool finished() const { return finished_; }

  const StaircaseRules& rules() const { return rules_; }
  int effective_reversals() const;
  const std::vector<double>& intensities() const { return intensities_; }
  const std::vector<bool>& responses() const { return responses_; }
  const std::vector<double>& reversal_intensities() const { return reversal_intensities_; }
  const std::vector<int>& reversal_trials() const { return reversal_trials_; }  // 1-based
  // The arithmetic (or geometric) mean of the last `count` reversal intensities, all of them when
  // fewer; NaN before the first reversal.
  double estimate(int count = 6) const;
  double geometric_estimate(int count = 6) const;

 private:
  enum class Direction { start, up, down };
  bool reversal_for(bool correct) const;
  void step(bool up);

  StaircaseRules rules_;
  double next_ = 0, step_size_ = 0;
  int counter_ = 0;  // +n after n correct in a row, −n after n wrong
  Direction direction_ = Direction::start;
  bool finished_ = false;
  std::vector<double> intensities_, reversal_intensities_;
  std::vector<bool> responses_;
  std::vector<int> reversal_trials_;
};

}  // namespace countershade::procedures
