#pragma once
// Depth-buffer unsharp masking (Luft et al. 2006). The spatial importance function
// ΔD = G*D − D of the normalised depth D drives one of four operators:
//   add       I' = I + λ·ΔD
//   contrast  I' = C(I)·α + I·(1−α), α = clamp(λ|ΔD|, 0, 1), C a global stretch or equalisation
//             (or a local contrast enhancement, for noisy depth)
//   darken    I' = I + λ·min(ΔD, 0)          (negative λ: a bright halo)
//   color     I' = I + λ·(|min(ΔD,0)|·c_cold + max(ΔD,0)·c_warm)
// applied to display RGB in [0,1] as in the paper, or with space = lab as a lightness-only change
// driven by the same scalar term (×100 to L* units; for `color`, the luminance of the colour term).

#include "enhance/method.h"

namespace countershade {

struct SpatialImportance {
  Image depth;       // D, normalised to [0,1] over valid pixels, 1 for background
  Image blurred;     // G*D
  Image importance;  // ΔD
  double sigma_px = 0;
};

// Computes D, G*D and ΔD for a view's depth map with the options' mapping and kernel.
SpatialImportance spatial_importance(const View& view, const MethodOptions& options);

class DepthUsmMethod final : public EnhancementMethod {
 public:
  std::string name() const override { return "depth-usm"; }
  std::string summary() const override { return "depth-buffer unsharp masking (Luft et al. 2006)"; }
  bool needs_depth() const override { return true; }
  void validate(const MethodOptions& options) const override;
  std::unique_ptr<PreparedEnhancement> prepare(const View& view, const MethodOptions& options) const override;
};

}  // namespace countershade
