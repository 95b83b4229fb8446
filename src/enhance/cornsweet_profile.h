#pragma once
// The lightness profile of a Cornsweet edge (docs/methods.md, "Cornsweet stimuli"), as a function
// of the distance d ≥ 0 from the edge, in units of the method's factor (ΔL* per unit of λ):
//   exponential (the default): side·exp(−d/w);
//   power, the lightness literature's (Boyaci et al. 2007; stimupy's `cornsweet`):
//     (1 − d/w)^a·(v_edge − v_plateau) for d < w, 0 beyond.
// In the image the edge is the vertical centre line. The power profile counts d from the pixels
// on either side of it, which therefore take the edge values exactly; the exponential one
// counts from pixel centres.

#include "core/image.h"

namespace countershade {

struct CornsweetProfile {
  bool power = false;
  double width = 1;        // w: pixels (image) or world units (surface)
  double exponent = 2.75;  // a (power)
  // The value at the edge on the dark (left) and the bright (right) side, before the method's
  // factor (ΔL* per unit of λ).
  double dark = -1, bright = 1;

  // 1 at the edge, falling to 0 (power: at w; exponential: towards infinity).
  double shape(double d) const;
  double at(double d, bool bright_side) const { return (bright_side ? bright : dark) * shape(d); }
};

// The profile at every pixel of a w × h image whose edge is its vertical centre line.
PixelDoubles cornsweet_image_profile(const CornsweetProfile& profile, int width, int height);

}  // namespace countershade
