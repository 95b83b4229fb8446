#pragma once
// Headroom against clipping (an experiment's "headroom"). At the top of a λ grid a method may push
// bright pixels past the display's white, or dark detail below its black, and clip them, a
// confound the audit flags. A study designer who needs a set that passes moves the scene's
// exposure, for all its stimuli alike: down against white clipping, up against black clipping.
// This finds how far, by rendering the scene again, just far enough that no condition clips more
// than the audit's limit at the grid's extremes.

#include <functional>
#include <memory>
#include <vector>

#include "enhance/view.h"

namespace countershade {

// The largest shares of pixels that a scene's conditions clip, at full scale and at black.
struct Clipped {
  double white = 0, black = 0;
  bool within(double limit) const { return white <= limit && black <= limit; }
};

// What the conditions clip at an exposure change of `stops`: white clipping must not rise as the
// exposure falls, nor black clipping as it rises.
using ClippedAt = std::function<Clipped(double stops)>;

// The exposure change closest to 0 at which both shares are within `limit`: 0 when that already
// holds, or when both ends clip too much; else down when white clips too much, up when black does,
// by doubling steps of 0.25, 0.5, 1 … stops and then bisecting to `resolution` stops. Where a step
// does not lower the share it is after, puts the other end over the limit, or reaches `floor`
// (`ceiling`), the search gives up and returns the last exposure it tried before that step (the
// limit is then not met; the audit says so).
double headroom_stops(const ClippedAt& clipped_at, double limit, double resolution = 0.05, double floor = -8,
                      double ceiling = 4);

// The largest shares of the view's pixels that any of its enhancing uses clips at full scale and
// at black (a channel at the top code or at 0 where the view's own image has not) at any of
// `lambdas`. With `hold_mean`, each stimulus is measured as the set writes it, after its mean is
// held (stimuli/mean_hold.h).
Clipped largest_clipped(const std::shared_ptr<const View>& view, const std::vector<double>& lambdas, int threads,
                        bool hold_mean);

}  // namespace countershade
