#pragma once
// Environment light as an equirectangular radiance map, with importance sampling.
// Convention: +y is up; direction d maps to u = atan2(d.x, -d.z)/(2π) (wrapped to [0,1)),
// v = acos(d.y)/π, so the map's centre column looks down -z and its top row is the zenith.

#include <memory>
#include <vector>

#include <glm/vec3.hpp>

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
    double pdf;  // per unit solid angle
  };
  // Picks a direction with probability proportional to luminance (importance sampling).
  Sample sample(double u1, double u2) const;
  double pdf(const glm::dvec3& direction) const;

  int width() const { return width_; }
  int height() const { return height_; }

 private:
  EnvironmentMap() = default;
  void build_distribution();
  const glm::dvec3& texel(int x, int y) const { return texels_[size_t(y) * width_ + x]; }

  int width_ = 0, height_ = 0;
  std::vector<glm::dvec3> texels_;
  std::vector<double> marginal_cdf_;     // height_+1 entries over rows
  std::vector<double> conditional_cdf_;  // height_ rows of width_+1 entries
  std::vector<double> row_weight_;       // unnormalised weight of each row
  double total_weight_ = 0;
};

glm::dvec3 equirect_direction(double u, double v);

}  // namespace countershade
