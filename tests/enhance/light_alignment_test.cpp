#include "enhance/light_alignment.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>
#include <random>
#include <vector>

#include "test_util.h"

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

// A ridge on a flat base (z up): two facets tilted by 30° towards +x and −x, lit from above, tilted
// towards +x by 0.1 and by 0.001 (so that the light has a side: straight along z it has none, and
// eq. 1 turns neither facet's light). Without enhancement the facets differ by about the tilt; at
// s = 1 the facet facing the light turns fully lit and the other nearly unlit, however small the
// tilt.
TEST(LightAlignment, ARidgeGetsOneLitAndOneUnlitSide) {
  const double a = 30.0 * std::acos(-1.0) / 180.0;
  const glm::dvec3 up(0, 0, 1), plus(std::sin(a), 0, std::cos(a)),
      minus(-std::sin(a), 0, std::cos(a));
  for (double tilt : {0.1, 0.001}) {
    const glm::dvec3 light = glm::normalize(glm::dvec3(tilt, 0, 1));
    const double plain = glm::dot(plus, light) - glm::dot(minus, light);
    const glm::dvec3 lit = align_one_scale(light, plus, up, 1.0, 3.0);
    const glm::dvec3 unlit = align_one_scale(light, minus, up, 1.0, 3.0);
    EXPECT_LT(plain, 1.1 * tilt);
    EXPECT_GT(glm::dot(plus, lit), 0.99) << tilt;
    EXPECT_LT(glm::dot(minus, unlit), 0.2) << tilt;
    EXPECT_GT(glm::dot(plus, lit) - glm::dot(minus, unlit), 0.5)
        << tilt;  // at least half the range [0, 1]
    EXPECT_NEAR(glm::length(lit), 1.0, 1e-12);
  }
  const glm::dvec3 above(0, 0, 1);  // no side: left as it is
  EXPECT_EQ(align_one_scale(above, plus, up, 1.0, 3.0), above);
  EXPECT_EQ(align_one_scale(above, minus, up, 1.0, 3.0), above);
}

TEST(LightAlignment, ZeroStrengthOrNoFeatureLeavesTheLightExactlyAsItWas) {
  const glm::dvec3 light = glm::normalize(glm::dvec3(0.3, -0.2, 0.9));
  const std::vector<glm::dvec3> normals = {glm::normalize(glm::dvec3(0.4, 0.1, 1)),
                                           glm::normalize(glm::dvec3(0.1, 0, 1)),
                                           glm::dvec3(0, 0, 1)};
  const std::vector<double> zero = {0.0, 0.0};
  const glm::dvec3 same = align_light(light, normals, zero, 3.0);
  EXPECT_EQ(same.x, light.x);
  EXPECT_EQ(same.y, light.y);
  EXPECT_EQ(same.z, light.z);
  const glm::dvec3 flat =
      align_one_scale(light, glm::dvec3(0, 0, 1), glm::dvec3(0, 0, 1), 1.0, 3.0);
  EXPECT_EQ(flat, light);  // λ2 = 0: the finer normal does not stand out from the coarser one
}

// Across the point where the guide switches from the normal to the tangent the rotation fades out,
// so the aligned light (and the shading) has no jump.
TEST(LightAlignment, NoJumpWhereTheGuideSwitchesSides) {
  const glm::dvec3 up(0, 0, 1), normal = glm::normalize(glm::dvec3(0.5, 0, 1));
  double largest_step = 0;
  glm::dvec3 previous =
      align_one_scale(glm::normalize(glm::dvec3(-0.2, 1, 0.3)), normal, up, 1.0, 3.0);
  for (int k = 1; k <= 4000; ++k) {
    const double t = -0.2 + 0.4 * k / 4000.0;  // the light sweeps across dot(l, x) = 0
    const glm::dvec3 aligned =
        align_one_scale(glm::normalize(glm::dvec3(t, 1, 0.3)), normal, up, 1.0, 3.0);
    largest_step =
        std::max(largest_step, std::abs(glm::dot(normal, aligned) - glm::dot(normal, previous)));
    previous = aligned;
  }
  EXPECT_LT(largest_step, 0.01);
}

// eq. 1 as written in docs/methods.md, with the C library's acos, sin and cos: the reference the
// lane-generic code must follow.
glm::dvec3 reference_one_scale(const glm::dvec3& light, const glm::dvec3& fine, const glm::dvec3& z,
                               double strength, double gamma) {
  const glm::dvec3 across = fine - z * glm::dot(fine, z);
  const double lambda2 = glm::length(across);
  if (strength <= 0 || lambda2 < 1e-12) return light;
  const glm::dvec3 x = across / lambda2;
  const bool bright = glm::dot(light, x) >= 0;
  const glm::dvec3 guide = bright ? fine : z * glm::dot(fine, x) - x * glm::dot(fine, z);
  const double angle = std::acos(std::clamp(glm::dot(light, guide), -1.0, 1.0));
  const glm::dvec3 light_across = light - z * glm::dot(light, z);
  if (glm::length(light_across) < 1e-12) return light;
  const glm::dvec3 side = light_across / glm::length(light_across);
  const double lambda1 =
      1 - 2 * std::acos(std::clamp(glm::dot(side, bright ? x : -x), -1.0, 1.0)) / std::numbers::pi;
  const double theta = std::min(strength, 1.0) * alignment_weight(lambda1 * lambda2, gamma) * angle;
  const glm::dvec3 axis = glm::cross(light, guide);
  if (theta <= 0 || glm::length(axis) < 1e-12) return light;
  const glm::dvec3 k = glm::normalize(axis);
  return glm::normalize(light * std::cos(theta) + glm::cross(k, light) * std::sin(theta) +
                        k * (glm::dot(k, light) * (1 - std::cos(theta))));
}

// Random unit vectors, with the degenerate cases mixed in: a finer normal equal to the coarser
// one, a light along the coarser normal, a light on the finer normal.
struct AlignmentCase {
  glm::dvec3 light, normals[3];
};
std::vector<AlignmentCase> alignment_cases(size_t count) {
  std::mt19937 random(7);
  std::normal_distribution<double> gauss;
  auto unit = [&] {
    return glm::normalize(glm::dvec3(gauss(random), gauss(random), gauss(random)));
  };
  std::vector<AlignmentCase> cases(count);
  for (size_t k = 0; k < count; ++k) {
    AlignmentCase& c = cases[k];
    c.normals[2] = unit();
    c.normals[1] = glm::normalize(c.normals[2] + 0.4 * unit());
    c.normals[0] = glm::normalize(c.normals[1] + 0.4 * unit());
    c.light = unit();
    if (k % 7 == 1) c.normals[1] = c.normals[2];
    if (k % 7 == 3) c.light = c.normals[1];
    if (k % 7 == 5) c.light = c.normals[0];
  }
  return cases;
}

TEST(LightAlignment, FollowsTheDefinitionWithTheLibrarysFunctions) {
  const std::vector<double> strengths = {0.8, 0.5};
  double worst = 0, worst_on_a_guide = 0;
  for (const AlignmentCase& c : alignment_cases(5000)) {
    const glm::dvec3 mid =
        reference_one_scale(c.light, c.normals[1], c.normals[2], strengths[1], 3.0);
    const glm::dvec3 expected =
        reference_one_scale(mid, c.normals[0], c.normals[1], strengths[0], 3.0);
    const double error = glm::length(align_light(c.light, c.normals, strengths, 3.0) - expected);
    // A light on the finer normal is at an angle of rounding size to its guide, where acos's slope
    // is unbounded: there a last-bit difference turns it by up to ~1e-8 either way.
    double& bucket = glm::dot(c.light, c.normals[0]) > 1 - 1e-9 ? worst_on_a_guide : worst;
    bucket = std::max(bucket, error);
  }
  EXPECT_LT(worst, 1e-12);
  EXPECT_LT(worst_on_a_guide, 1e-9);
}

TEST(LightAlignment, ABlockAlignsEveryPointAsAlignLightDoesBitForBit) {
  testing::with_and_without_avx512([] {
    const std::vector<double> strengths = {1.0, 0.35};
    const AlignmentWeight weight(2.5);
    const std::vector<AlignmentCase> cases = alignment_cases(3 * kAlignmentBlock);
    AlignmentBlock block;
    for (size_t first = 0; first < cases.size();
         first += kAlignmentBlock - 3) {  // blocks not filled to the end
      const size_t count = std::min(kAlignmentBlock - 3, cases.size() - first);
      for (size_t j = 0; j < count; ++j)
        for (int c = 0; c < 3; ++c) {
          block.light[c][j] = cases[first + j].light[c];
          for (int k = 0; k < 3; ++k) block.vectors[k][c][j] = cases[first + j].normals[k][c];
        }
      align_light_block(block, count, 3, strengths, weight.damping());
      for (size_t j = 0; j < count; ++j) {
        const glm::dvec3 one =
            align_light(cases[first + j].light, cases[first + j].normals, strengths, weight);
        for (int c = 0; c < 3; ++c) ASSERT_EQ(block.aligned[c][j], one[c]) << "point " << first + j;
      }
    }
  });
}

}  // namespace
}  // namespace countershade
