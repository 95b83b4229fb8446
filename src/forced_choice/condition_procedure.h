#pragma once
// One condition's procedure in a forced-choice study: the plug-in the experiment names
// (procedures/registry.h) on the condition's λ grid (docs/forced-choice.md, "Intensities"), ended
// by its own rule or by the study's max_trials.

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "procedures/choice_block.h"
#include "procedures/procedure.h"

namespace countershade::forced_choice {

// The block as the experiment file gives it (procedures/choice_block.h).
using procedures::ChoiceConfig;
using procedures::ConditionSelection;
using procedures::Layout;
using procedures::layout_name;
using procedures::parse_choice_config;

using ChoiceGrid = procedures::Grid;
using Intensity = procedures::Intensity;

class ConditionProcedure {
 public:
  // Throws InputError (naming `where`) when the procedure cannot work on this grid.
  ConditionProcedure(const procedures::ProcedureBlock& block, int max_trials,
                     const ChoiceGrid& grid, uint64_t seed, const std::string& where);

  Intensity next() const { return procedure_->next(); }
  bool ready() const { return procedure_->ready(); }
  void record(const Intensity& shown, bool correct);
  bool finished() const { return trials_ >= max_trials_ || procedure_->finished(); }
  int trials() const { return trials_; }
  // The procedure's state after the last answer, for the record.
  nlohmann::ordered_json state() const { return procedure_->state(); }

 private:
  std::unique_ptr<procedures::Procedure> procedure_;
  int max_trials_ = 0;
  int trials_ = 0;
};

}  // namespace countershade::forced_choice
