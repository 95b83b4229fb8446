#pragma once
// Multi-scale normals in `surface` mode (docs/methods.md, "Multi-scale normals"): the normals of
// every object smoothed over its surface with the uniform 1-ring Laplacian of 3D unsharp masking,
// renormalised after each step. n_1 is the shading normal; n_{k+1} is smoothed over the width
// σ_k = σ_1·1.7^(k−1) (world units), k = 1 … S−1. Computed on the mesh, they do not change when
// the camera moves.

#include <glm/vec3.hpp>
#include <memory>
#include <vector>

#include "enhance/normal_field.h"
#include "render/hooks.h"
#include "render/scene.h"

namespace countershade {

struct SurfacePoint;

class MultiscaleNormals final : public NormalScaleField {
 public:
  // Smooths the normals of every object of `scene` for scales 2 … `scales`.
  MultiscaleNormals(std::shared_ptr<const Scene> scene, double sigma1, int scales, int threads = 0);
  // The same, shared with the last scenes asked for whose meshes are identical (compared vertex by
  // vertex) at the same σ_1 and S: the light-direction variants of one scene smooth once.
  static std::shared_ptr<const MultiscaleNormals> shared(std::shared_ptr<const Scene> scene,
                                                         double sigma1, int scales,
                                                         int threads = 0);

  int scales() const override { return scales_; }
  // n_k (k = 2 … S) at a surface point, interpolated over its triangle and normalised.
  glm::dvec3 at(const SurfacePoint& point, int k) const;
  // n_1 … n_S at a shading point into n[0 … S−1]: n_1 its shading normal, the smoothed ones turned
  // to the side the viewer sees as the shading normal is.
  void at_shading_point(const ShadingInputs& s, glm::dvec3* n) const override;
  // {"mode": "surface", "smoothing_iterations": per object, scale and component}.
  nlohmann::json describe() const override;
  // The smoothing iterations of scale k (2 … S) per component of object `object`.
  const std::vector<int>& iterations(size_t object, int k) const {
    return iterations_[object][size_t(k - 2)];
  }

 private:
  bool same_input(const Scene& scene, double sigma1, int scales) const;

  std::shared_ptr<const Scene> scene_;
  double sigma1_;
  int scales_;
  std::vector<std::vector<std::vector<glm::vec3>>> vertex_normals_;  // [object][k − 2][vertex]
  std::vector<std::vector<std::vector<int>>> iterations_;            // [object][k − 2][component]
};

}  // namespace countershade
