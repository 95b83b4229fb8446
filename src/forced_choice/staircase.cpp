#include "forced_choice/staircase.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace countershade::forced_choice {

Staircase::Staircase(StaircaseRules rules) : rules_(std::move(rules)) {
  next_ = rules_.start;
  step_size_ = rules_.step_sizes.front();
}

int Staircase::effective_reversals() const {
  const int listed = int(rules_.step_sizes.size());
  return std::max(rules_.n_reversals.value_or(listed), listed);
}

// Whether this answer turns the staircase around. Before the first reversal (with the initial
// rule) every answer steps, so any change of direction is a reversal; afterwards only a completed
// run of nDown correct or nUp wrong answers steps.
bool Staircase::reversal_for(bool correct) const {
  const bool initial = reversal_intensities_.empty() && rules_.apply_initial_rule;
  if (initial) return correct ? direction_ == Direction::up : direction_ == Direction::down;
  if (counter_ >= rules_.n_down) return direction_ == Direction::up;
  if (counter_ <= -rules_.n_up) return direction_ == Direction::down;
  return false;
}

void Staircase::step(bool up) {
  const double s = step_size_;
  switch (rules_.step_type) {
    case StepType::lin:
      next_ += up ? s : -s;
      break;
    case StepType::log:
      next_ = up ? next_ * std::pow(10.0, s) : next_ / std::pow(10.0, s);
      break;
    case StepType::db:
      next_ = up ? next_ * std::pow(10.0, s / 20.0) : next_ / std::pow(10.0, s / 20.0);
      break;
  }
  if (up && rules_.max_value && next_ > *rules_.max_value) next_ = *rules_.max_value;
  if (!up && rules_.min_value && next_ < *rules_.min_value) next_ = *rules_.min_value;
  counter_ = 0;
}

bool Staircase::add_response(bool correct, std::optional<double> shown_value) {
  const double shown = shown_value.value_or(next_);
  intensities_.push_back(shown);
  const bool same_as_before = !responses_.empty() && responses_.back() == correct;
  responses_.push_back(correct);
  counter_ = correct ? (same_as_before ? counter_ + 1 : 1) : (same_as_before ? counter_ - 1 : -1);

  const bool initial = reversal_intensities_.empty() && rules_.apply_initial_rule;
  const bool reversal = reversal_for(correct);
  if (initial)
    direction_ = correct ? Direction::down : Direction::up;
  else if (counter_ >= rules_.n_down)
    direction_ = Direction::down;
  else if (counter_ <= -rules_.n_up)
    direction_ = Direction::up;
  if (reversal) {
    reversal_trials_.push_back(int(intensities_.size()));
    reversal_intensities_.push_back(shown);
    const size_t n = std::min(reversal_intensities_.size(), rules_.step_sizes.size() - 1);
    step_size_ = rules_.step_sizes[n];
  }
  finished_ = int(reversal_intensities_.size()) >= effective_reversals() &&
              int(intensities_.size()) >= rules_.n_trials;
  // The trial of the first reversal still steps by the initial 1-up/1-down rule.
  if (initial)
    step(!correct);
  else if (counter_ >= rules_.n_down)
    step(false);
  else if (counter_ <= -rules_.n_up)
    step(true);
  return reversal;
}

double Staircase::estimate(int count) const {
  if (reversal_intensities_.empty()) return std::numeric_limits<double>::quiet_NaN();
  const size_t n = std::min(reversal_intensities_.size(), size_t(count));
  double sum = 0;
  for (size_t i = reversal_intensities_.size() - n; i < reversal_intensities_.size(); ++i)
    sum += reversal_intensities_[i];
  return sum / double(n);
}

double Staircase::geometric_estimate(int count) const {
  if (reversal_intensities_.empty()) return std::numeric_limits<double>::quiet_NaN();
  const size_t n = std::min(reversal_intensities_.size(), size_t(count));
  double sum = 0;
  for (size_t i = reversal_intensities_.size() - n; i < reversal_intensities_.size(); ++i)
    sum += std::log(reversal_intensities_[i]);
  return std::exp(sum / double(n));
}

}  // namespace countershade::forced_choice
