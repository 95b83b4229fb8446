#pragma once
// The multi-scale normals n_1 … n_S that the shading methods read at a shading point, in either
// mode of docs/methods.md: `surface` (smoothed over the mesh, enhance/multiscale_normals.h) or
// `image` (bilateral-filtered G-buffer normals, enhance/image_normals.h).

#include <nlohmann/json.hpp>

#include "render/hooks.h"

namespace countershade {

// Each scale's smoothing width is the last one's times this: n_{k+1} is smoothed over
// σ_k = σ_1·kNormalScaleRatio^(k−1), in world units or pixels by the mode.
inline constexpr double kNormalScaleRatio = 1.7;

class NormalScaleField {
 public:
  virtual ~NormalScaleField() = default;
  virtual int scales() const = 0;
  // n_1 … n_S into n[0 … S−1]: n_1 the shading normal, the smoother ones on the side the viewer
  // sees.
  virtual void at_shading_point(const ShadingInputs& s, glm::dvec3* n) const = 0;
  // What the manifest records about how the normals were made (the mode and its own figures).
  virtual nlohmann::json describe() const = 0;
};

}  // namespace countershade
