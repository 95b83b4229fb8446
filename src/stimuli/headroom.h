#pragma once
// Headroom against clipping (an experiment's "headroom"). At the top of a λ grid a method may push
// bright pixels past the display's white, or dark detail below its black, and clip them, a
// confound the audit flags. A study designer who needs a set that passes changes the scene's
// display, for all its stimuli alike: a lower exposure leaves room above the brightest pixel, a
// black level (Exposure::black) room below the darkest. This finds how much of each, by rendering
// the scene again, just enough that no condition clips more than the audit's limit at the grid's
// extremes.
#include <functional>
#include <memory>
#include <vector>

#include "enhance/view.h"

namespace countershade {

// The largest shares of pixels that a scene's conditions clip, at full scale and at black, and
// at both ends together: the share the audit limits, one condition's at one λ. Where that is not
// measured (both < 0), the sum of the two ends bounds it.
struct Clipped {
  double white = 0, black = 0, both = -1;
  double total() const { return both >= 0 ? both : white + black; }
  bool within(double limit) const { return total() <= limit; }
};

// A change of the scene's display.
struct Headroom {
  double exposure_stops = 0;  // added to the scene's exposure
  double black_level = 0;     // added to the scene's black level
  bool operator==(const Headroom&) const = default;
};

// What the conditions clip under a change of the display: white clipping must not rise as the
// exposure falls, nor black clipping as the black level rises.
using ClippedAt = std::function<Clipped(const Headroom&)>;

// How a search moves one setting away from 0: steps of `first`, 2·first, 4·first … toward `end`
// until one passes, then halving to `resolution`.
struct HeadroomSearch {
  double first, end, resolution;
};
inline constexpr HeadroomSearch kExposureSearch{-0.25, -8.0, 0.05};           // stops
inline constexpr HeadroomSearch kBlackLevelSearch{1.0 / 64, 0.5, 1.0 / 256};  // share of full scale

// The smallest change that clips within `limit`. First the exposure, lowered only as far as
// white clipping alone needs; then, at that exposure, the black level, raised until both ends
// together are within the limit (a black level clips no white: lifting the dark end compresses the
// lightness scale, so methods that work in L* clip less at white too). Each search gives up where
// a step does not lower the share it is after, where the black level clips more white than
// before and more than the limit, or at its end, and keeps the last setting it tried before that
// step (the limit is then not met; the audit says so).
Headroom find_headroom(const ClippedAt& clipped_at, double limit,
                       const HeadroomSearch& exposure = kExposureSearch,
                       const HeadroomSearch& black_level = kBlackLevelSearch);

// The largest shares of the view's pixels that any of its enhancing uses clips at full scale and
// at black (a channel at the top code or at 0 where the view's own image has not) at any of
// `lambdas`. With `hold_mean`, each stimulus is measured as the set writes it, after its mean is
// held (stimuli/mean_hold.h).
Clipped largest_clipped(const std::shared_ptr<const View>& view, const std::vector<double>& lambdas,
                        int threads, bool hold_mean);

}  // namespace countershade
