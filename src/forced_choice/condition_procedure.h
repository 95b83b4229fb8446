#pragma once
// One condition's procedure in λ units on the stimulus set's grid (docs/forced-choice.md,
// "Intensities"): a staircase steps in λ and shows the nearest grid λ; QUEST works in log10 λ,
// its recommendation is rounded to the nearest grid λ and updated with the λ shown; constant
// stimuli show each listed λ (which must be on the grid) a number of times in a seeded order.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "forced_choice/choice_config.h"
#include "forced_choice/quest.h"
#include "forced_choice/staircase.h"

namespace countershade::forced_choice {

// The λ > 0 a set shows, with their grid indices, increasing.
struct ChoiceGrid {
  std::vector<double> lambdas;
  std::vector<int> indices;
  // The grid point nearest λ (linear distance; the lower one on a tie).
  size_t nearest(double lambda) const;
};

struct Intensity {
  double requested = 0;  // what the procedure asked for
  size_t grid = 0;       // the grid point shown
};

class ConditionProcedure {
 public:
  // Throws InputError (naming `where`) when the procedure cannot work on this grid.
  ConditionProcedure(const ChoiceConfig& config, const ChoiceGrid& grid, uint64_t seed,
                     const std::string& where);

  Intensity next() const;
  void record(const Intensity& shown, bool correct);
  bool finished() const;
  int trials() const { return trials_; }
  // The procedure's state after the last answer, for the record (QUEST's mean and SD; a
  // staircase's reversals and estimate).
  nlohmann::ordered_json state() const;

 private:
  const ChoiceConfig& config_;
  const ChoiceGrid& grid_;
  std::optional<Staircase> staircase_;
  std::optional<Quest> quest_;
  std::vector<size_t> constant_order_;  // grid points in the order shown
  int trials_ = 0;
};

}  // namespace countershade::forced_choice
