#include "forced_choice/condition_procedure.h"

#include "core/error.h"

namespace countershade::forced_choice {

ConditionProcedure::ConditionProcedure(const procedures::ProcedureBlock& block, int max_trials,
                                       const ChoiceGrid& grid, uint64_t seed,
                                       const std::string& where)
    : max_trials_(max_trials) {
  if (grid.lambdas.empty()) throw_input_error(where, "the set has no λ above 0 to show");
  procedure_ = block.settings->start(grid, seed, where);
}

void ConditionProcedure::record(const Intensity& shown, bool correct) {
  procedure_->record(shown, correct);
  ++trials_;
}

}  // namespace countershade::forced_choice
