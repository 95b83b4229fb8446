#pragma once
// sin and cos for sampling directions: a polynomial after range reduction, accurate to a few
// units in the last place and the same on every processor. (The C library's sin and cos pick
// other code paths by processor, with or without fused multiply-adds, and may round the last bit
// differently; the renderer calls them for every sample.)

#include <cmath>

namespace countershade {

// sin and cos of 2π·turns.
inline void sincos_turns(double turns, double& s, double& c) {
  // The octant's centre angle (k + ½)·π/4, then the Taylor series of the rest, |φ| ≤ π/8.
  double u = turns - std::floor(turns);
  int k = int(u * 8.0);
  k = k > 7 ? 7 : k;
  const double phi = (u - (k + 0.5) * 0.125) * 6.283185307179586476925;
  const double p2 = phi * phi;
  const double sp =
      phi *
      (1.0 + p2 * (-1.0 / 6 +
                   p2 * (1.0 / 120 +
                         p2 * (-1.0 / 5040 +
                               p2 * (1.0 / 362880 + p2 * (-1.0 / 39916800 + p2 / 6227020800.0))))));
  const double cp =
      1.0 +
      p2 * (-0.5 +
            p2 * (1.0 / 24 + p2 * (-1.0 / 720 +
                                   p2 * (1.0 / 40320 + p2 * (-1.0 / 3628800 + p2 / 479001600.0)))));
  // The centre's sine and cosine are ±sin π/8 and ±cos π/8: octants 0, 3, 4 and 7 lie next to the
  // x axis (the sine is the small one), 0-3 have a positive sine and 0, 1, 6 and 7 a positive
  // cosine. Selections rather than a table, so that loops of this function vectorise.
  constexpr double kNear = 0.38268343236508978, kFar = 0.92387953251128674;
  const bool near_x = ((k + 1) & 2) == 0;
  const double sa = (k < 4 ? 1.0 : -1.0) * (near_x ? kNear : kFar);
  const double ca = (((k + 2) & 4) == 0 ? 1.0 : -1.0) * (near_x ? kFar : kNear);
  s = sp * ca + cp * sa;
  c = cp * ca - sp * sa;
}

}  // namespace countershade
