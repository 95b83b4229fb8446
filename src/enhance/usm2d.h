#pragma once
// 2D image unsharp masking of lightness (the classic baseline): C = L* − G_σ * L*, Δ = λ·C,
// composed lightness-only. σ in pixels, as % of the image diagonal, or from a kernel size K%
// (σ = K/4).

#include "enhance/method.h"

namespace countershade {

// Validates the image-space width options shared by usm2d and depth-usm.
void validate_image_width(const std::string& method, const MethodOptions& options);

class Usm2dMethod final : public EnhancementMethod {
 public:
  std::string name() const override { return "usm2d"; }
  std::string summary() const override { return "2D unsharp masking of lightness in image space"; }
  void validate(const MethodOptions& options) const override;
  std::unique_ptr<PreparedEnhancement> prepare(const View& view, const MethodOptions& options) const override;
};

}  // namespace countershade
