#pragma once
// Environment light as an equirectangular radiance map, with importance sampling.
// Convention: +y is up; direction d maps to u = atan2(d.x, -d.z)/(2π) (wrapped to [0,1)),
// v = acos(d.y)/π, so the map's centre column looks down -z and its top row is the zenith.

#include <glm/vec3.hpp>
#include <memory>
#include <vector>

#include "core/image.h"

namespace countershade {

struct SkyParameters {
  glm::dvec3 zenith{0.35, 0.55, 1.0};
  glm::dvec3 horizon{1.0, 1.0, 1.0};
  glm::dvec3 ground{0.35, 0.3, 0.25};
};

class EnvironmentMap {
 public:
  // From linear RGB texels (at least 3 channels; extra channels are ignored).
  explicit EnvironmentMap(const Image& linear_rgb);
  static EnvironmentMap constant(const glm::dvec3& radiance);
  static EnvironmentMap sky(const SkyParameters& sky, int width = 256, int height = 128);

  glm::dvec3 radiance(const glm::dvec3& direction) const;

  struct Sample {
    glm::dvec3 direction;
    double pdf;           // per unit solid angle
    glm::dvec3 radiance;  // the map's (bilinear) radiance in that direction
  };
  // Picks a texel with probability proportional to luminance · sinθ (O(1), alias method) using
  // u1, and a uniform point inside it using u2 and u3.
  Sample sample(double u1, double u2, double u3) const;
  double pdf(const glm::dvec3& direction) const;

  int width() const { return width_; }
  int height() const { return height_; }

 private:
  EnvironmentMap() = default;
  void build_distribution();
  void find_constant_rows();
  const glm::dvec3& texel(int x, int y) const { return texels_[size_t(y) * width_ + x]; }
  glm::dvec3 radiance_at(double u, double v) const;
  double pdf_of_texel(size_t index, double sin_theta) const;

  int width_ = 0, height_ = 0;
  std::vector<glm::dvec3> texels_;
  // One radiance per row where every row is constant (a sky, a constant map): a lookup then
  // interpolates between rows only, and needs no azimuth (atan2) at all.
  std::vector<glm::dvec3> rows_;
  std::vector<double> probability_;  // per texel, sums to 1
  std::vector<double> alias_threshold_;
  std::vector<uint32_t> alias_;
};

glm::dvec3 equirect_direction(double u, double v);

}  // namespace countershade
