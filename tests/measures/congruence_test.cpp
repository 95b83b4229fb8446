#include "measures/congruence.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/random.h"

namespace countershade {
namespace {

constexpr int kSize = 64;

// A hemisphere of radius 28 px seen from above: depth 100 − height inside the disc, background
// (infinite depth) outside.
Image sphere_depth() {
  Image depth(kSize, kSize, 1, std::numeric_limits<float>::infinity());
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const double r2 = (x - 31.5) * (x - 31.5) + (y - 31.5) * (y - 31.5);
      if (r2 < 28.0 * 28.0) depth.at(x, y) = float(100.0 - std::sqrt(28.0 * 28.0 - r2));
    }
  return depth;
}

// L* = 100 × the depth normalised over the foreground (background 100).
Image lightness_from_depth(const Image& depth) {
  float lo = INFINITY, hi = -INFINITY;
  for (float d : depth.pixels)
    if (std::isfinite(d)) lo = std::min(lo, d), hi = std::max(hi, d);
  Image l(depth.width, depth.height, 1, 100.0f);
  for (size_t i = 0; i < l.pixels.size(); ++i)
    if (std::isfinite(depth.pixels[i])) l.pixels[i] = 100.0f * (depth.pixels[i] - lo) / (hi - lo);
  return l;
}

TEST(Congruence, ShadingThatIsItsOwnDepthScoresOneAndNoiseScoresFarLower) {
  const Image depth = sphere_depth();
  const Congruence own = congruence(lightness_from_depth(depth), depth);
  EXPECT_GE(own.score, 0.8);
  EXPECT_NEAR(own.score, 1.0, 1e-6);  // identical fields: equal magnitudes, parallel orientations
  Image noise(kSize, kSize, 1);
  SampleStream random(7, 0, 0, 0);
  for (float& v : noise.pixels) v = float(100.0 * random.next());
  const Congruence noisy = congruence(noise, depth);
  EXPECT_LE(noisy.score, own.score - 0.3) << noisy.score;
  EXPECT_GT(noisy.score, 0.0);
}

TEST(Congruence, AFlatImageScoresExactlyZero) {
  const Congruence flat = congruence(Image(kSize, kSize, 1, 50.0f), sphere_depth());
  EXPECT_EQ(flat.score, 0.0);
  EXPECT_FALSE(std::isnan(flat.score));
  for (float v : flat.map.pixels) EXPECT_EQ(v, 0.0f);
  // No foreground at all: no interior pixels, score 0.
  const Congruence empty = congruence(Image(8, 8, 1, 50.0f), Image(8, 8, 1, 0.0f));
  EXPECT_EQ(empty.interior_pixels, 0u);
  EXPECT_EQ(empty.score, 0.0);
}

// A depth ramp along x: shading that ramps along x agrees everywhere (score 1); shading that ramps
// along y is perpendicular everywhere (score 0).
TEST(Congruence, OrientationsDecideTheScore) {
  Image depth(kSize, kSize, 1), along_x(kSize, kSize, 1), along_y(kSize, kSize, 1);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      depth.at(x, y) = 10.0f + float(x);
      along_x.at(x, y) = 100.0f * float(x) / (kSize - 1);
      along_y.at(x, y) = 100.0f * float(y) / (kSize - 1);
    }
  EXPECT_NEAR(congruence(along_x, depth).score, 1.0, 1e-6);
  EXPECT_NEAR(congruence(along_y, depth).score, 0.0, 1e-6);
  // Interior pixels: every pixel but the one-pixel border.
  EXPECT_EQ(congruence(along_x, depth).interior_pixels, size_t(kSize - 2) * (kSize - 2));
}

TEST(Congruence, PercentileInterpolatesBetweenOrderStatistics) {
  EXPECT_DOUBLE_EQ(percentile({4, 1, 3, 2}, 0.5), 2.5);
  EXPECT_NEAR(percentile({4, 1, 3, 2}, 0.99), 3.97, 1e-12);
  EXPECT_DOUBLE_EQ(percentile({5}, 0.99), 5.0);
  EXPECT_DOUBLE_EQ(percentile({}, 0.99), 0.0);
}

TEST(Congruence, RefusesImagesOfDifferentSizes) {
  EXPECT_THROW(congruence(Image(4, 4, 1), Image(5, 4, 1)), std::invalid_argument);
  EXPECT_THROW(congruence(Image(4, 4, 3), Image(4, 4, 1)), std::invalid_argument);
}

}  // namespace
}  // namespace countershade
