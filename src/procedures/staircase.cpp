#include "procedures/staircase.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

namespace countershade::procedures {
namespace {

constexpr int kMostTrials = 100000;

// minVal / maxVal: absent and null both mean no bound, as in StairHandler.
std::optional<double> optional_bound(const ParameterBag& bag, const std::string& key) {
  if (!bag.given(key)) return std::nullopt;
  return bag.required_number(key);
}

std::vector<double> step_sizes(const ParameterBag& bag) {
  const std::vector<double> steps = bag.numbers("stepSizes", {4.0});
  if (steps.empty()) bag.fail("stepSizes", "must list at least one step size");
  for (double s : steps)
    if (!(s > 0)) bag.fail("stepSizes", "step sizes must be above 0");
  return steps;
}

void check_staircase_rules(const StaircaseRules& r, const ParameterBag& bag,
                           const std::string& type) {
  if (r.min_value && r.max_value && !(*r.min_value < *r.max_value))
    bag.fail("maxVal", "must be above minVal");
  if ((r.min_value && r.start < *r.min_value) || (r.max_value && r.start > *r.max_value))
    bag.fail("startVal", "must lie within [minVal, maxVal]");
  if (r.step_type == StepType::lin) return;
  if (!(r.start > 0))
    bag.fail("startVal", "must be above 0 for " + type + " steps (they multiply)");
  if (r.min_value && !(*r.min_value > 0))
    bag.fail("minVal", "must be above 0 for " + type + " steps (they multiply)");
}

}  // namespace

StaircaseRules read_staircase_rules(const ParameterBag& bag) {
  StaircaseRules r;
  r.start = bag.required_number("startVal");
  r.step_sizes = step_sizes(bag);
  const std::string type = bag.choice("stepType", "db", {"lin", "log", "db"});
  r.step_type = type == "lin" ? StepType::lin : type == "log" ? StepType::log : StepType::db;
  r.n_up = int(bag.integer_in("nUp", 1, 1, 1000));
  r.n_down = int(bag.integer_in("nDown", 3, 1, 1000));
  r.n_trials = int(bag.integer_in("nTrials", 0, 0, kMostTrials));
  if (bag.given("nReversals")) r.n_reversals = int(bag.integer_in("nReversals", 0, 0, kMostTrials));
  r.min_value = optional_bound(bag, "minVal");
  r.max_value = optional_bound(bag, "maxVal");
  r.apply_initial_rule = bag.boolean("applyInitialRule", true);
  check_staircase_rules(r, bag, type);
  return r;
}

std::vector<ParameterDoc> staircase_parameter_docs() {
  return {
      {"startVal", "", "First intensity (λ), required"},
      {"stepSizes", "4", "Step size, or a list that advances one entry at each reversal"},
      {"stepType", "db", "lin (add), log (log10 units) or db (20·log10 units)"},
      {"nUp", "1", "Wrong answers in a row that make the task easier"},
      {"nDown", "3", "Right answers in a row that make it harder"},
      {"nTrials", "0", "Trials at least (the staircase also waits for its reversals)"},
      {"nReversals", "", "Reversals at least; at least the number of step sizes (null: that)"},
      {"minVal", "", "Lowest intensity (null: none)"},
      {"maxVal", "", "Highest intensity (null: none)"},
      {"applyInitialRule", "true", "1-up 1-down until the first reversal"},
  };
}

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

}  // namespace countershade::procedures
