#pragma once
// Degrees of visual angle on a flat screen (docs/display.md).

#include <cmath>
#include <numbers>

namespace countershade {

// The pixels that one degree spans at the centre of a screen `width_mm` wide with `width_px`
// pixels, seen from `distance_mm`: 2·d·tan(0.5°) mm.
inline double pixels_per_degree(double width_mm, double width_px, double distance_mm) {
  return 2.0 * distance_mm * std::tan(0.5 * std::numbers::pi / 180.0) * width_px / width_mm;
}

}  // namespace countershade
