#include "enhance/light_alignment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

namespace countershade {
namespace {

TEST(LightAlignment, WeightIsMonotoneFromZeroToOneAndTheIdentityForGammaZero) {
  for (double gamma : {0.0, 1.0, 3.0, 8.0}) {
    EXPECT_EQ(alignment_weight(0.0, gamma), 0.0);
    EXPECT_DOUBLE_EQ(alignment_weight(1.0, gamma), 1.0);
    double previous = 0;
    for (int k = 1; k <= 1000; ++k) {
      const double w = alignment_weight(k / 1000.0, gamma);
      EXPECT_GE(w, previous);
      previous = w;
    }
  }
  for (double x : {0.1, 0.37, 0.5, 0.9}) EXPECT_DOUBLE_EQ(alignment_weight(x, 0.0), x);
  EXPECT_GT(alignment_weight(0.2, 3.0), alignment_weight(0.2, 1.0));  // larger γ, faster transition
}

// A ridge on a flat base (z up): two facets tilted by 30° towards +x and −x, lit slightly from +x.
// Without enhancement the facets differ little; at s = 1 the facet facing the light turns fully lit
// and the other nearly unlit.
TEST(LightAlignment, ARidgeGetsOneLitAndOneUnlitSide) {
  const double a = 30.0 * std::acos(-1.0) / 180.0;
  const glm::dvec3 up(0, 0, 1), plus(std::sin(a), 0, std::cos(a)), minus(-std::sin(a), 0, std::cos(a));
  const glm::dvec3 light = glm::normalize(glm::dvec3(0.1, 0, 1));
  const double plain = glm::dot(plus, light) - glm::dot(minus, light);
  const glm::dvec3 lit = align_one_scale(light, plus, up, 1.0, 3.0);
  const glm::dvec3 unlit = align_one_scale(light, minus, up, 1.0, 3.0);
  EXPECT_LT(plain, 0.11);
  EXPECT_GT(glm::dot(plus, lit), 0.99);
  EXPECT_LT(glm::dot(minus, unlit), 0.2);
  EXPECT_GT(glm::dot(plus, lit) - glm::dot(minus, unlit), 0.5);  // at least half the range [0, 1]
  EXPECT_NEAR(glm::length(lit), 1.0, 1e-12);
}

TEST(LightAlignment, ZeroStrengthOrNoFeatureLeavesTheLightExactlyAsItWas) {
  const glm::dvec3 light = glm::normalize(glm::dvec3(0.3, -0.2, 0.9));
  const std::vector<glm::dvec3> normals = {glm::normalize(glm::dvec3(0.4, 0.1, 1)), glm::normalize(glm::dvec3(0.1, 0, 1)),
                                           glm::dvec3(0, 0, 1)};
  const std::vector<double> zero = {0.0, 0.0};
  const glm::dvec3 same = align_light(light, normals, zero, 3.0);
  EXPECT_EQ(same.x, light.x);
  EXPECT_EQ(same.y, light.y);
  EXPECT_EQ(same.z, light.z);
  const glm::dvec3 flat = align_one_scale(light, glm::dvec3(0, 0, 1), glm::dvec3(0, 0, 1), 1.0, 3.0);
  EXPECT_EQ(flat, light);  // λ2 = 0: the finer normal does not stand out from the coarser one
}

// Across the point where the guide switches from the normal to the tangent the rotation fades out,
// so the aligned light (and the shading) has no jump.
TEST(LightAlignment, NoJumpWhereTheGuideSwitchesSides) {
  const glm::dvec3 up(0, 0, 1), normal = glm::normalize(glm::dvec3(0.5, 0, 1));
  double largest_step = 0;
  glm::dvec3 previous = align_one_scale(glm::normalize(glm::dvec3(-0.2, 1, 0.3)), normal, up, 1.0, 3.0);
  for (int k = 1; k <= 4000; ++k) {
    const double t = -0.2 + 0.4 * k / 4000.0;  // the light sweeps across dot(l, x) = 0
    const glm::dvec3 aligned = align_one_scale(glm::normalize(glm::dvec3(t, 1, 0.3)), normal, up, 1.0, 3.0);
    largest_step = std::max(largest_step, std::abs(glm::dot(normal, aligned) - glm::dot(normal, previous)));
    previous = aligned;
  }
  EXPECT_LT(largest_step, 0.01);
}

}  // namespace
}  // namespace countershade
