#include "render/directions.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "core/fast_math.h"

namespace countershade {

TangentFrame::TangentFrame(const glm::dvec3& axis) : n(axis) {
  // Duff et al. 2017, branchless ONB.
  double sign = std::copysign(1.0, n.z);
  double a = -1.0 / (sign + n.z);
  double c = n.x * n.y * a;
  t = {1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x};
  b = {c, sign + n.y * n.y * a, -n.y};
}

glm::dvec3 direction_around(const TangentFrame& frame, double cos_theta, double turns) {
  double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
  double sin_phi, cos_phi;
  sincos_turns(turns, sin_phi, cos_phi);
  return glm::normalize(sin_theta * cos_phi * frame.t + sin_theta * sin_phi * frame.b +
                        cos_theta * frame.n);
}

glm::dvec3 sample_cone(const TangentFrame& axis, double cos_max, double u1, double u2) {
  return direction_around(axis, 1.0 - u1 * (1.0 - cos_max), u2);
}

glm::dvec3 sample_cosine_hemisphere(const TangentFrame& frame, double u1, double u2) {
  double r = std::sqrt(u1), sin_phi, cos_phi;
  sincos_turns(u2, sin_phi, cos_phi);
  return glm::normalize(r * cos_phi * frame.t + r * sin_phi * frame.b +
                        std::sqrt(std::max(0.0, 1.0 - u1)) * frame.n);
}

}  // namespace countershade
