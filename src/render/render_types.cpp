#include "render/render_types.h"

#include <cmath>

#include "core/color.h"

namespace countershade {

double display_luminance(const glm::dvec3& radiance, const Exposure& exposure) {
  glm::dvec3 c;
  for (int i = 0; i < 3; ++i) c[i] = exposure(radiance[i]);
  return luminance_of(c);
}

glm::dvec3 triangle_sample_barycentrics(int j, int k) {
  // Stratified in the first coordinate, golden-ratio sequence in the second, warped uniformly
  // onto the triangle.
  double r1 = (j + 0.5) / k, r2 = std::fmod(0.5 + 0.6180339887498949 * j, 1.0);
  double s = std::sqrt(r1);
  return {1.0 - s, s * (1.0 - r2), s * r2};
}

}  // namespace countershade
