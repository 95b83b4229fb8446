#include "core/fast_math.h"

#include <gtest/gtest.h>

#include <cmath>

namespace countershade {
namespace {

TEST(FastMath, SinAndCosOfTurnsMatchTheLibrary) {
  double worst = 0;
  for (int i = -2000; i <= 6000; ++i) {
    const double turns = i / 4000.0 + 1e-7 * i;
    double s, c;
    sincos_turns(turns, s, c);
    worst = std::max({worst, std::abs(s - std::sin(2 * M_PI * turns)),
                      std::abs(c - std::cos(2 * M_PI * turns))});
  }
  EXPECT_LT(worst, 1e-14);
  double s, c;
  sincos_turns(0.25, s, c);
  EXPECT_NEAR(s, 1.0, 1e-16);
  EXPECT_NEAR(c, 0.0, 1e-16);
}

}  // namespace
}  // namespace countershade
