#pragma once
// A test value per pixel from the surface point the pixel sees: a layer or mask attached to the
// surface, for the reprojection measures' tests.

#include <cmath>
#include <functional>
#include <vector>

#include "enhance/view.h"
#include "render/camera.h"

namespace countershade::testing {

// f(world point, object) at every pixel with a finite depth; 0 elsewhere.
inline std::vector<float> surface_values(const View& v,
                                         const std::function<double(const glm::dvec3&, int)>& f) {
  const CameraRays rays(v.scene->camera);
  std::vector<float> out(v.depth.size(), 0.0f);
  for (int y = 0; y < v.height(); ++y)
    for (int x = 0; x < v.width(); ++x) {
      const size_t i = size_t(y) * size_t(v.width()) + size_t(x);
      if (std::isfinite(v.depth[i]))
        out[i] = float(f(rays.point_at_depth(x + 0.5, y + 0.5, v.depth[i]), v.object_at(i)));
    }
  return out;
}

}  // namespace countershade::testing
