#pragma once
// Multi-scale normals in `image` mode (docs/methods.md, "Multi-scale normals"; the paper's own
// implementation): the G-buffer's normals filtered by a bilateral filter whose range kernel acts
// on depth, so that silhouettes stay sharp. n_{k+1} is the filter of n_1 with a spatial σ_k =
// σ_1·1.7^(k−1) pixels. They belong to one view: when the camera moves, they change.

#include <glm/vec3.hpp>
#include <memory>
#include <vector>

#include "enhance/normal_field.h"
#include "enhance/view.h"
#include "render/camera.h"

namespace countershade {

class ImageNormals final : public NormalScaleField {
 public:
  // `depth_tolerance`: the range kernel's σ relative to the pixel's depth (0.02: neighbours 2 %
  // nearer or farther weigh e^{−1/2}).
  ImageNormals(const View& view, double sigma1_px, int scales, double depth_tolerance,
               int threads = 0);

  int scales() const override { return scales_; }
  // n_k (k = 2 … S) at a film position (pixels), interpolated bilinearly over the object pixels
  // among the four nearest and normalised; `fallback` when there are none.
  glm::dvec3 at(const glm::dvec2& film, int k, const glm::dvec3& fallback) const;
  void at_shading_point(const ShadingInputs& s, glm::dvec3* n) const override;
  nlohmann::json describe() const override;

 private:
  CameraRays camera_;
  int width_, height_, scales_;
  double sigma1_, depth_tolerance_;
  std::vector<char> object_;
  std::vector<std::vector<glm::vec3>> normals_;  // [k − 2][pixel]
};

}  // namespace countershade
