#include "render/environment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>

#include "core/random.h"

namespace countershade {
namespace {

constexpr double kPi = std::numbers::pi;

// ∫ L dω by midpoint quadrature over (θ, φ).
glm::dvec3 integrate(const EnvironmentMap& map) {
  const int nt = 400, np = 800;
  glm::dvec3 sum(0.0);
  for (int i = 0; i < nt; ++i)
    for (int j = 0; j < np; ++j) {
      double v = (i + 0.5) / nt, u = (j + 0.5) / np;
      sum +=
          map.radiance(equirect_direction(u, v)) * std::sin(kPi * v) * (kPi / nt) * (2 * kPi / np);
    }
  return sum;
}

TEST(Environment, DirectionMappingConvention) {
  glm::dvec3 zenith = equirect_direction(0.3, 0.0), forward = equirect_direction(0.0, 0.5);
  EXPECT_NEAR(zenith.y, 1.0, 1e-12);
  EXPECT_NEAR(forward.z, -1.0, 1e-12);  // the map's centre-left column looks down -z
  EXPECT_NEAR(equirect_direction(0.25, 0.5).x, 1.0, 1e-12);
}

TEST(Environment, ImportanceSamplingIsUnbiasedAndConsistent) {
  SkyParameters sky;
  sky.zenith = {0.1, 0.2, 2.0};
  sky.horizon = {3.0, 2.5, 2.0};
  EnvironmentMap map = EnvironmentMap::sky(sky, 64, 32);
  glm::dvec3 reference = integrate(map);
  glm::dvec3 estimate(0.0);
  const int n = 400000;
  SampleStream random(5, 0, 0, 0);
  for (int i = 0; i < n; ++i) {
    auto s = map.sample(random.next(), random.next(), random.next());
    ASSERT_NEAR(glm::length(s.direction), 1.0, 1e-12);
    ASSERT_NEAR(s.pdf, map.pdf(s.direction), 1e-6 * s.pdf);
    estimate += s.radiance / s.pdf;
  }
  estimate /= double(n);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(estimate[c], reference[c], 0.01 * reference[c]) << c;
}

// A map whose rows are each one colour (a sky) is looked up between rows only; the radiance is
// the bilinear lookup's, which the same map with one far texel changed still takes.
TEST(Environment, AMapOfConstantRowsGivesTheBilinearRadiance) {
  SkyParameters sky;
  sky.zenith = {0.1, 0.2, 2.0};
  const EnvironmentMap rows = EnvironmentMap::sky(sky, 64, 32);
  Image image(64, 32, 3);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) {
      const glm::dvec3 c = rows.radiance(equirect_direction((x + 0.5) / 64, (y + 0.5) / 32));
      for (int k = 0; k < 3; ++k) image.at(x, y, k) = float(c[k]);
    }
  const EnvironmentMap same_rows(image);
  image.at(0, 31, 0) += 0.5f;  // one texel at the nadir: the map is no longer row-constant
  const EnvironmentMap bilinear(image);
  SampleStream random(3, 0, 0, 0);
  for (int i = 0; i < 2000; ++i) {
    const glm::dvec3 d = equirect_direction(random.next(), 0.9 * random.next());
    const glm::dvec3 a = same_rows.radiance(d), b = bilinear.radiance(d);
    for (int k = 0; k < 3; ++k) ASSERT_NEAR(a[k], b[k], 1e-12 * (1 + b[k])) << i;
  }
  EXPECT_NE(same_rows.radiance(equirect_direction(0.0, 0.999))[0],
            bilinear.radiance(equirect_direction(0.0, 0.999))[0]);
}

TEST(Environment, ConstantMapIntegratesToFourPi) {
  EnvironmentMap map = EnvironmentMap::constant(glm::dvec3(2.0));
  EXPECT_NEAR(integrate(map).x, 8 * kPi, 1e-3);
  EXPECT_DOUBLE_EQ(map.radiance(glm::normalize(glm::dvec3(0.3, -0.2, 0.9))).y, 2.0);
}

}  // namespace
}  // namespace countershade
