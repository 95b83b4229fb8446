#pragma once
// The audit's bracket check, when the viewing condition is known (docs/observer.md, "The
// audit's bracket check"): each condition's λ grid should start below the image-computable
// observer's λ at 1 JND, with at least three grid steps below it, and reach its λ at 4 JND, so
// that an adjustment study can find λ_Low and λ_High and a forced-choice study has levels below
// threshold.

#include <optional>
#include <string>

#include "audit/audit.h"
#include "observer/set_prediction.h"

namespace countershade {

inline constexpr int kStepsBelowThreshold = 3;

// A λ grid, as an experiment file gives it.
struct SuggestedGrid {
  double min = 0, max = 0, step = 0;
  int count() const;
  std::string json() const;  // {"min": 0, "max": 0.14, "step": 0.0035}
};

// The grid that brackets every condition that responds: a step of a quarter of the smallest λ at
// 1 JND (rounded down to 1, 2 or 5 × 10^k), up to a quarter above the largest λ at 4 JND. Where a
// condition never reaches a level on the set's grid, its λ is extrapolated, the response being
// linear in λ. None when no condition responds.
std::optional<SuggestedGrid> bracketing_grid(const observer::SetPrediction& prediction);

// One check per condition (controls that respond at no λ pass), and a note that suggests a grid
// when any falls short. `grid` is the set's.
void add_bracket_checks(AuditReport& report, const observer::SetPrediction& prediction,
                        const LambdaGridInfo& grid, double ppd);

}  // namespace countershade
