#pragma once
// Unit directions drawn around an axis: the light and environment samples of the shader.

#include <glm/vec3.hpp>

namespace countershade {

// An orthonormal frame around a unit axis (Duff et al. 2017): made once per shading point or
// light, and shared by every direction drawn around it.
struct TangentFrame {
  explicit TangentFrame(const glm::dvec3& axis);
  glm::dvec3 t, b, n;
};

// The unit vector at cos θ = `cos_theta` from the frame's axis and azimuth 2π·`turns`.
glm::dvec3 direction_around(const TangentFrame& frame, double cos_theta, double turns);
// Unit vector in the cone of half-angle acos(`cos_max`) around the axis, uniform over the cap.
glm::dvec3 sample_cone(const TangentFrame& axis, double cos_max, double u1, double u2);
// Cosine-weighted direction in the hemisphere around the frame's axis.
glm::dvec3 sample_cosine_hemisphere(const TangentFrame& frame, double u1, double u2);

// sample_cosine_hemisphere and sample_cone for kDirectionLanes points at once, side by side in
// vector lanes: the same operations in the same order, so the same bits. They write the
// directions' x, y and z.
constexpr int kDirectionLanes = 8;
void sample_cosine_hemisphere_lanes(const TangentFrame& frame, const double* u1, const double* u2,
                                    double* x, double* y, double* z);
void sample_cone_lanes(const TangentFrame& axis, double cos_max, const double* u1, const double* u2,
                       double* x, double* y, double* z);

}  // namespace countershade
