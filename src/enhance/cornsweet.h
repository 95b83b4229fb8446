#pragma once
// Cornsweet profiles (Purves et al.'s 2D-vs-3D comparison, docs/methods): two regions of equal
// lightness meet at an edge; near it, L* changes by ±A·exp(−|d|/w), with opposite signs on the
// two sides. A = λ·amplitude (ΔL*), w = σ.
//   mode "image":   the edge is the image's vertical centre line, d and w in pixels (a flat 2D
//                   stimulus when the view is a uniform field);
//   mode "surface": the edge is a 3D line (edge_point, edge_direction), d is the distance of each
//                   pixel's surface point from it and w is in world units; pixels whose normal
//                   lies within 60° of bright_normal take +, the others −.

#include "enhance/method.h"

namespace countershade {

class CornsweetMethod final : public EnhancementMethod {
 public:
  std::string name() const override { return "cornsweet"; }
  std::string summary() const override { return "Cornsweet profile across an edge, in the image or on a surface"; }
  void validate(const MethodOptions& options) const override;
  std::unique_ptr<PreparedEnhancement> prepare(const View& view, const MethodOptions& options) const override;
};

}  // namespace countershade
