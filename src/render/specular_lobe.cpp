#include "render/specular_lobe.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>

namespace countershade {
namespace {

constexpr double kPi = std::numbers::pi;

// The density of a half vector at cos θh = c over solid angle.
double half_vector_pdf(const Material& m, double c) {
  if (c <= 0) return 0.0;
  if (m.specular == SpecularModel::blinn_phong)
    return (m.shininess + 1.0) / (2.0 * kPi) * std::pow(c, m.shininess);
  return ggx_distribution(ggx_alpha2(m), c) * c;
}

// cos θh for a uniform u, by inverting the half vector's distribution.
double half_vector_cosine(const Material& m, double u) {
  if (m.specular == SpecularModel::blinn_phong) return std::pow(u, 1.0 / (m.shininess + 1.0));
  const double a2 = ggx_alpha2(m);
  return std::sqrt(std::max(0.0, (1.0 - u) / (1.0 + (a2 - 1.0) * u)));
}

}  // namespace

double ggx_alpha2(const Material& m) { return std::pow(m.roughness, 4.0); }

double ggx_distribution(double alpha2, double cos_h) {
  const double d = cos_h * cos_h * (alpha2 - 1.0) + 1.0;
  return alpha2 / (kPi * d * d);
}

bool has_specular_lobe(const Material& m) { return m.specular != SpecularModel::none; }

std::optional<glm::dvec3> sample_specular_lobe(const Material& m, const TangentFrame& n,
                                               const glm::dvec3& wo, double u1, double u2) {
  const glm::dvec3 h = direction_around(n, half_vector_cosine(m, u1), u2);
  const double wo_h = glm::dot(wo, h);
  if (wo_h <= 0) return std::nullopt;
  return glm::normalize(2.0 * wo_h * h - wo);
}

double specular_lobe_pdf(const Material& m, const glm::dvec3& n, const glm::dvec3& wo,
                         const glm::dvec3& wi) {
  const glm::dvec3 sum = wi + wo;
  const double length = glm::length(sum);
  if (length <= 1e-12) return 0.0;
  const glm::dvec3 h = sum / length;
  const double wo_h = glm::dot(wo, h);
  return wo_h > 0 ? half_vector_pdf(m, glm::dot(n, h)) / (4.0 * wo_h) : 0.0;
}

}  // namespace countershade
