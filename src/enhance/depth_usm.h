#pragma once
// Depth-buffer unsharp masking (Luft et al. 2006). The spatial importance function
// ΔD = G*D − D of the normalised depth D drives one of four operators:
//   add       I' = I + λ·ΔD
//   contrast  I' = C(I)·α + I·(1−α), α = clamp(λ|ΔD|, 0, 1), C a global stretch or equalisation
//             (or a local contrast enhancement, for noisy depth)
//   darken    I' = I + λ·min(ΔD, 0)          (negative λ: a bright halo)
//   color     I' = I + λ·(|min(ΔD,0)|·c_cold + max(ΔD,0)·c_warm)
// applied to display RGB in [0,1] as in the paper, or with space = lab as a lightness-only change
// driven by the same scalar term (×100 to L* units). `color` shifts hue, so it has no lab form.
// The method lives in depth_usm.cpp; this is its spatial importance, which tests use too.

#include <optional>
#include <utility>

#include "enhance/method.h"

namespace countershade {

struct SpatialImportance {
  Image depth;       // D, normalised to [0,1] over valid pixels, 1 for background
  Image blurred;     // G*D
  Image importance;  // ΔD
  // The operators' terms per pixel: the means of min(ΔD, 0) and max(ΔD, 0) over the pixel's area,
  // which differ from those of the pixel's own ΔD only at depth edges (enhance/depth_coverage.h).
  Image darker, lighter;
  double sigma_px = 0;
};

struct DepthMapping {
  bool zbuffer = false;                 // the perspective z-buffer value instead of linear depth
  std::optional<double> z_near, z_far;  // its planes (default: the valid depth range)
  // The eye depths D maps to 0 and 1, clamped (default: the image's own valid range). Held fixed,
  // D of a surface point does not change when something else in the scene moves: in a sequence a
  // per-frame range would let every frame's whole ΔD swell and shrink with the nearest object.
  std::optional<std::pair<double, double>> range;
};

// D, G*D and ΔD of a view's depth map with Gaussian σ in pixels.
SpatialImportance spatial_importance(const View& view, const DepthMapping& mapping, double sigma_px,
                                     int threads = 0);

// Histogram-based global contrast over all `values` (all channels jointly, so colour balance is
// kept), in [0, range]: a 1st–99th percentile stretch, or an equalisation that maps the lowest
// value present to 0 and the highest to `range`.
class GlobalContrast {
 public:
  GlobalContrast(const std::vector<float>& values, double range, bool equalize);
  double operator()(double v) const;

 private:
  static constexpr size_t kBins = 4096;
  size_t bin(float v) const;
  double range_;
  bool equalize_;
  std::vector<double> cdf_;
  double cdf_min_ = 0, lo_ = 0, hi_ = 1;
};

}  // namespace countershade
