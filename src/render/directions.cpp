#include "render/directions.h"

#include <algorithm>
#include <cmath>

#include "core/fast_math.h"
#include "core/isa.h"

namespace countershade {

TangentFrame::TangentFrame(const glm::dvec3& axis) : n(axis) {
  // Duff et al. 2017, branchless ONB.
  double sign = std::copysign(1.0, n.z);
  double a = -1.0 / (sign + n.z);
  double c = n.x * n.y * a;
  t = {1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x};
  b = {c, sign + n.y * n.y * a, -n.y};
}

namespace {

// The direction at `across` (sin θ) and `along` (cos θ) from the axis and azimuth 2π·turns, one
// sample's or one lane's: (across·cos φ)·t + (across·sin φ)·b + along·n, normalised as
// v · (1 / sqrt((x² + y²) + z²)). The single functions and the lanes both use it, so they agree.
inline void direction_lane(const TangentFrame& f, double across, double along, double turns,
                           double& x, double& y, double& z) {
  double sin_phi, cos_phi;
  sincos_turns(turns, sin_phi, cos_phi);
  const double a = across * cos_phi, c = across * sin_phi;
  const double vx = a * f.t.x + c * f.b.x + along * f.n.x,
               vy = a * f.t.y + c * f.b.y + along * f.n.y,
               vz = a * f.t.z + c * f.b.z + along * f.n.z;
  const double inverse = 1.0 / std::sqrt(vx * vx + vy * vy + vz * vz);
  x = vx * inverse, y = vy * inverse, z = vz * inverse;
}

}  // namespace

glm::dvec3 direction_around(const TangentFrame& frame, double cos_theta, double turns) {
  glm::dvec3 d;
  direction_lane(frame, std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta)), cos_theta, turns,
                 d.x, d.y, d.z);
  return d;
}

glm::dvec3 sample_cone(const TangentFrame& axis, double cos_max, double u1, double u2) {
  return direction_around(axis, 1.0 - u1 * (1.0 - cos_max), u2);
}

glm::dvec3 sample_cosine_hemisphere(const TangentFrame& frame, double u1, double u2) {
  glm::dvec3 d;
  direction_lane(frame, std::sqrt(u1), std::sqrt(std::max(0.0, 1.0 - u1)), u2, d.x, d.y, d.z);
  return d;
}

namespace {

COUNTERSHADE_CLONES
void cosine_lanes(const TangentFrame& f, const double* __restrict u1, const double* __restrict u2,
                  double* __restrict x, double* __restrict y, double* __restrict z) {
  for (int i = 0; i < kDirectionLanes; ++i)
    direction_lane(f, std::sqrt(u1[i]), std::sqrt(std::max(0.0, 1.0 - u1[i])), u2[i], x[i], y[i],
                   z[i]);
}

COUNTERSHADE_CLONES
void cone_lanes(const TangentFrame& f, double cos_max, const double* __restrict u1,
                const double* __restrict u2, double* __restrict x, double* __restrict y,
                double* __restrict z) {
  for (int i = 0; i < kDirectionLanes; ++i) {
    const double cos_theta = 1.0 - u1[i] * (1.0 - cos_max);
    direction_lane(f, std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta)), cos_theta, u2[i], x[i],
                   y[i], z[i]);
  }
}

}  // namespace

void sample_cosine_hemisphere_lanes(const TangentFrame& frame, const double* u1, const double* u2,
                                    double* x, double* y, double* z) {
  cosine_lanes(frame, u1, u2, x, y, z);
}

void sample_cone_lanes(const TangentFrame& axis, double cos_max, const double* u1, const double* u2,
                       double* x, double* y, double* z) {
  cone_lanes(axis, cos_max, u1, u2, x, y, z);
}

}  // namespace countershade
