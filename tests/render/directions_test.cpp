#include "render/directions.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>

#include "core/random.h"

namespace countershade {
namespace {

double unit(uint64_t key) { return double(mix64(key) >> 11) * 0x1p-53; }

// The lanes promise the scalar functions' bits: stimuli stay the same bytes whichever is used.
TEST(Directions, DirectionsInLanesAreTheScalarOnesBitForBit) {
  double u1[kDirectionLanes], u2[kDirectionLanes], x[kDirectionLanes], y[kDirectionLanes],
      z[kDirectionLanes];
  for (uint64_t round = 0; round < 20000; ++round) {
    const glm::dvec3 axis = glm::normalize(
        glm::dvec3(unit(4 * round) - 0.5, unit(4 * round + 1) - 0.5, unit(4 * round + 2) - 0.5));
    const TangentFrame frame(axis);
    for (int i = 0; i < kDirectionLanes; ++i) {
      u1[i] = unit(1000003 * round + uint64_t(2 * i));
      u2[i] = unit(1000003 * round + uint64_t(2 * i + 1));
    }
    if (round % 4 == 1)  // the ends and every octant's edges of the azimuth
      for (int i = 0; i < kDirectionLanes; ++i) {
        u1[i] = i == 0 ? 0.0 : u1[i];
        u2[i] = double(i) / 8.0 + (round % 8 == 1 ? 0.0 : -0x1p-53);
      }
    sample_cosine_hemisphere_lanes(frame, u1, u2, x, y, z);
    for (int i = 0; i < kDirectionLanes; ++i) {
      const glm::dvec3 d = sample_cosine_hemisphere(frame, u1[i], u2[i]);
      ASSERT_EQ(d.x, x[i]) << round << " " << i;
      ASSERT_EQ(d.y, y[i]) << round << " " << i;
      ASSERT_EQ(d.z, z[i]) << round << " " << i;
    }
    // Cones from a light's disc (a few degrees) to the whole sphere.
    const double cos_max = std::cos(unit(7 * round + 5) * (round % 3 == 0 ? 0.1 : 3.14159));
    sample_cone_lanes(frame, cos_max, u1, u2, x, y, z);
    for (int i = 0; i < kDirectionLanes; ++i) {
      const glm::dvec3 d = sample_cone(frame, cos_max, u1[i], u2[i]);
      ASSERT_EQ(d.x, x[i]) << round << " " << i;
      ASSERT_EQ(d.y, y[i]) << round << " " << i;
      ASSERT_EQ(d.z, z[i]) << round << " " << i;
    }
  }
}

}  // namespace
}  // namespace countershade
