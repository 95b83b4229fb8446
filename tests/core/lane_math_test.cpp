#include "core/lane_math.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>

namespace countershade {
namespace {

using Lanes = double __attribute__((vector_size(32)));
using LaneBits = int64_t __attribute__((vector_size(32)));

TEST(LaneMath, AcosMatchesTheLibraryOverItsWholeDomain) {
  double worst = 0;
  for (int k = 0; k <= 200000; ++k) {
    const double x = -1.0 + k / 100000.0;
    worst = std::max(worst, std::abs(acos_lanes(x) - std::acos(x)));
  }
  EXPECT_LT(worst, 5e-16);
  EXPECT_EQ(acos_lanes(1.0), 0.0);
  EXPECT_DOUBLE_EQ(acos_lanes(-1.0), std::numbers::pi);
  EXPECT_DOUBLE_EQ(acos_lanes(0.0), std::numbers::pi / 2);
}

TEST(LaneMath, SinCosMatchTheLibraryFromZeroToPi) {
  double worst = 0;
  for (int k = 0; k <= 200000; ++k) {
    const double theta = std::numbers::pi * k / 200000.0;
    double s, c;
    sincos_lanes(theta, s, c);
    worst = std::max({worst, std::abs(s - std::sin(theta)), std::abs(c - std::cos(theta))});
  }
  EXPECT_LT(worst, 2.5e-16);
  double s, c;
  sincos_lanes(0.0, s, c);
  EXPECT_EQ(s, 0.0);
  EXPECT_EQ(c, 1.0);
}

// The vector form gives every lane exactly the scalar's value, the point of writing them once.
TEST(LaneMath, LanesEqualTheScalarBitForBit) {
  for (int k = 0; k < 1000; ++k) {
    const Lanes x = {-1.0 + k / 500.0, 0.5 + 1e-3 * k / 1000, -0.5 - 1e-9 * k, std::sin(0.1 * k)};
    const Lanes theta = {std::numbers::pi * k / 1000.0, 0.785 + k * 1e-6, 1e-3 * k,
                         std::numbers::pi - 1e-3 * k};
    const Lanes a = acos_lanes(x), r = sqrt_lanes(x * x);
    Lanes s, c;
    sincos_lanes(theta, s, c);
    for (int lane = 0; lane < 4; ++lane) {
      double ss, cc;
      sincos_lanes(theta[lane], ss, cc);
      EXPECT_EQ(a[lane], acos_lanes(x[lane]));
      EXPECT_EQ(r[lane], std::sqrt(x[lane] * x[lane]));
      EXPECT_EQ(s[lane], ss);
      EXPECT_EQ(c[lane], cc);
    }
  }
}

double exp_of(double x) { return exp_lanes<double, int64_t>(x); }

TEST(LaneMath, ExpMatchesTheLibraryWithinTwoUlp) {
  double worst = 0;
  for (int k = -400000; k <= 400000; ++k) {
    const double x = k / 1000.0;
    worst = std::max(worst, std::abs(exp_of(x) / std::exp(x) - 1.0));
  }
  EXPECT_LT(worst, 4.5e-16);
  EXPECT_EQ(exp_of(0.0), 1.0);
  EXPECT_NEAR(exp_of(-700.0) / std::exp(-700.0), 1.0, 1e-15);
  EXPECT_NEAR(exp_of(700.0) / std::exp(700.0), 1.0, 1e-15);
  EXPECT_EQ(exp_of(1000.0), exp_of(700.0));  // clamped
  const Lanes x = {-3.25, 0.0, 1e-9, 12.5};
  const Lanes e = exp_lanes<Lanes, LaneBits>(x);
  for (int lane = 0; lane < 4; ++lane) EXPECT_EQ(e[lane], exp_of(x[lane]));
}

TEST(LaneMath, UnusedLanesMayHoldNonFiniteValues) {
  const Lanes x = {NAN, INFINITY, -INFINITY, 0.5};
  const Lanes a = acos_lanes(x);
  Lanes s, c;
  sincos_lanes(x, s, c);
  EXPECT_DOUBLE_EQ(a[3], std::acos(0.5));
  EXPECT_DOUBLE_EQ(s[3], std::sin(0.5));
  EXPECT_TRUE(std::isnan(s[0]));
  const Lanes clamped = exp_lanes<Lanes, LaneBits>(x);
  EXPECT_EQ(clamped[0], exp_of(-700.0));  // NaN: clamped, no trap
}

}  // namespace
}  // namespace countershade
