#include "enhance/light_alignment.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace countershade {
namespace {

constexpr double kDegenerate = 1e-12;

double angle_between(const glm::dvec3& a, const glm::dvec3& b) { return std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0)); }

// Rodrigues' rotation of v about the unit axis k by θ.
glm::dvec3 rotate(const glm::dvec3& v, const glm::dvec3& k, double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  return v * c + glm::cross(k, v) * s + k * (glm::dot(k, v) * (1 - c));
}

}  // namespace

AlignmentWeight::AlignmentWeight(double gamma) : damping_(std::exp(-gamma)) {}

double AlignmentWeight::operator()(double x) const {
  x = std::clamp(x, 0.0, 1.0);
  return x / (damping_ * (1 - x) + x);
}

double alignment_weight(double x, double gamma) { return AlignmentWeight(gamma)(x); }

glm::dvec3 align_one_scale(const glm::dvec3& light, const glm::dvec3& fine, const glm::dvec3& coarse, double strength,
                           const AlignmentWeight& weight) {
  if (strength <= 0) return light;
  // Frame: z the coarser vector, x the finer one's part across it (its length is λ2).
  const glm::dvec3 z = coarse;
  const glm::dvec3 across = fine - z * glm::dot(fine, z);
  const double lambda2 = glm::length(across);
  if (lambda2 < kDegenerate) return light;  // no feature at this scale
  const glm::dvec3 x = across / lambda2;
  // The guide: the finer vector when the light lies on its side of the frame, else the tangent
  // to it in the (x, z) plane on the light's side (so that the light is turned to graze it).
  const bool bright = glm::dot(light, x) >= 0;
  const glm::dvec3 guide = bright ? fine : z * glm::dot(fine, x) - x * glm::dot(fine, z);
  const double angle = angle_between(light, guide);
  // λ1 measures how far the light is from the switching point dot(l, x) = 0, by the angle between
  // the light and the guide projected across z (the guide's projection is ±x): 1 when the light
  // lies along it, 0 at the switch, so the rotation fades out on both sides and the shading has
  // no jump there. (The 3D angle would leave a jump of up to 0.7 in n·l.)
  const glm::dvec3 light_across = light - z * glm::dot(light, z);
  const double across_length = glm::length(light_across);
  if (across_length < kDegenerate) return light;  // light along the coarser normal: no side to choose
  const double lambda1 = 1 - 2 * angle_between(light_across / across_length, bright ? x : -x) / std::numbers::pi;
  const double theta = std::min(strength, 1.0) * weight(lambda1 * lambda2) * angle;
  const glm::dvec3 axis = glm::cross(light, guide);
  const double axis_length = glm::length(axis);
  if (theta <= 0 || axis_length < kDegenerate) return light;
  return glm::normalize(rotate(light, axis / axis_length, theta));
}

glm::dvec3 align_light(const glm::dvec3& light, std::span<const glm::dvec3> vectors, std::span<const double> strengths,
                       const AlignmentWeight& weight) {
  glm::dvec3 l = light;
  for (size_t i = vectors.size() - 1; i-- > 0;)
    l = align_one_scale(l, vectors[i], vectors[i + 1], i < strengths.size() ? strengths[i] : 0.0, weight);
  return l;
}

}  // namespace countershade
