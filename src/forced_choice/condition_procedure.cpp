#include "forced_choice/condition_procedure.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/number_format.h"
#include "core/random.h"

namespace countershade::forced_choice {

size_t ChoiceGrid::nearest(double lambda) const {
  const size_t hi =
      size_t(std::lower_bound(lambdas.begin(), lambdas.end(), lambda) - lambdas.begin());
  if (hi == 0) return 0;
  if (hi == lambdas.size()) return hi - 1;
  return lambda - lambdas[hi - 1] <= lambdas[hi] - lambda ? hi - 1 : hi;
}

namespace {

// The grid point of a listed λ; one off the grid is an InputError.
size_t on_grid(const ChoiceGrid& grid, double lambda, const std::string& where) {
  const size_t i = grid.nearest(lambda);
  if (std::abs(grid.lambdas[i] - lambda) > 1e-9)
    throw_input_error(where, "λ " + format_value(lambda) + " is not on the set's λ grid (" +
                                 format_value(grid.lambdas.front()) + " to " +
                                 format_value(grid.lambdas.back()) + ")");
  return i;
}

std::vector<size_t> constant_order(const ChoiceConfig& c, const ChoiceGrid& grid, uint64_t seed,
                                   const std::string& where) {
  std::vector<size_t> order;
  for (double lambda : c.levels) {
    const size_t point = on_grid(grid, lambda, where + ".lambdas");
    for (int r = 0; r < c.repetitions; ++r) order.push_back(point);
  }
  SampleStream random(seed, 211, 0, 0);  // Fisher–Yates from the condition's own stream
  for (size_t i = order.size(); i > 1; --i)
    std::swap(order[i - 1], order[std::min(size_t(random.next() * double(i)), i - 1)]);
  return order;
}

}  // namespace

ConditionProcedure::ConditionProcedure(const ChoiceConfig& config, const ChoiceGrid& grid,
                                       uint64_t seed, const std::string& where)
    : config_(config), grid_(grid) {
  if (grid.lambdas.empty()) throw_input_error(where, "the set has no λ above 0 to show");
  switch (config.kind) {
    case ProcedureKind::constant:
      constant_order_ = constant_order(config, grid, seed, where);
      break;
    case ProcedureKind::staircase:
      staircase_.emplace(config.adaptive.staircase);
      break;
    case ProcedureKind::quest: {
      quest_.emplace(config.adaptive.quest, where);
      const double lo = std::log10(grid.lambdas.front()), hi = std::log10(grid.lambdas.back());
      if (quest_->highest() < lo || quest_->lowest() > hi)
        throw_input_error(
            where + ".range",
            "QUEST's thresholds (log10 λ " + format_value(round_to(quest_->lowest(), 3)) + " to " +
                format_value(round_to(quest_->highest(), 3)) +
                ") exclude the set's λ grid (log10 λ " + format_value(round_to(lo, 3)) + " to " +
                format_value(round_to(hi, 3)) + ")");
      break;
    }
  }
}

Intensity ConditionProcedure::next() const {
  double requested = 0;
  switch (config_.kind) {
    case ProcedureKind::constant: {
      const size_t point = constant_order_[size_t(trials_)];
      return {grid_.lambdas[point], point};
    }
    case ProcedureKind::staircase:
      requested = staircase_->next_intensity();
      break;
    case ProcedureKind::quest:
      requested = std::pow(10.0, quest_->quantile());
      break;
  }
  return {requested, grid_.nearest(requested)};
}

void ConditionProcedure::record(const Intensity& shown, bool correct) {
  const double lambda = grid_.lambdas[shown.grid];
  if (staircase_) staircase_->add_response(correct, lambda);
  if (quest_) quest_->update(std::log10(lambda), correct);
  ++trials_;
}

bool ConditionProcedure::finished() const {
  if (trials_ >= config_.max_trials) return true;
  switch (config_.kind) {
    case ProcedureKind::constant:
      return size_t(trials_) >= constant_order_.size();
    case ProcedureKind::staircase:
      return staircase_->finished();
    case ProcedureKind::quest:
      return trials_ >= config_.trials;
  }
  return true;
}

nlohmann::ordered_json ConditionProcedure::state() const {
  if (quest_)
    return {{"quest_mean", quest_->mean()},
            {"quest_sd", quest_->sd()},
            {"quest_quantile", quest_->quantile()}};
  if (staircase_) {
    nlohmann::ordered_json j = {{"reversals", staircase_->reversal_intensities().size()},
                                {"next_intensity", staircase_->next_intensity()}};
    if (!staircase_->reversal_intensities().empty()) j["estimate"] = staircase_->estimate();
    return j;
  }
  return nlohmann::ordered_json::object();
}

}  // namespace countershade::forced_choice
