#pragma once
// Headroom against clipping (an experiment's "headroom"). At the top of a λ grid a method may push
// bright pixels past the display's white and clip them, a confound the audit flags. A study
// designer who needs a set that passes lowers the scene's exposure, for all its stimuli alike:
// this finds how far, by rendering the scene again, just far enough that no condition clips more
// than the audit's limit at the grid's extremes.

#include <functional>
#include <memory>
#include <vector>

#include "enhance/view.h"

namespace countershade {

// The largest share of pixels clipped at an exposure change of `stops` (≤ 0). It must not rise as
// `stops` falls.
using ClippedAt = std::function<double(double stops)>;

// The largest exposure change ≤ 0 at which clipped_at ≤ limit: 0 when that already holds, else
// found by doubling steps of −0.25, −0.5, −1 … stops and then bisecting to `resolution` stops.
// Where a step down does not lower the share, or at `floor`, the search gives up and returns the
// last exposure it tried before that step (the limit is then not met; the audit says so).
double headroom_stops(const ClippedAt& clipped_at, double limit, double resolution = 0.05, double floor = -8);

// The largest share of the view's pixels that any of its enhancing uses clips at full scale (a
// channel at the top code where the view's own image has not) at any of `lambdas`. Clipping at
// black does not shrink with the exposure and is not counted. With `hold_mean`, each stimulus is
// measured as the set writes it, after its mean is held (stimuli/mean_hold.h).
double largest_clipped_share(const std::shared_ptr<const View>& view, const std::vector<double>& lambdas, int threads,
                             bool hold_mean);

}  // namespace countershade
