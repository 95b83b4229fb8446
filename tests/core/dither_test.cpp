// Dithering 16-bit stimuli to 8 bits: the mean over frames, reproducibility, and a pattern that
// changes from frame to frame.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/dither.h"

namespace countershade {
namespace {

// Every 16-bit value from a ramp, and over 64 frames each pixel's mean 8-bit level is within 0.02
// of its target v/257 (the bound is 1/64 = 0.0156), starting at any frame.
TEST(Dither, TheMeanOverSixtyFourFramesIsTheSixteenBitValue) {
  std::vector<uint16_t> values(65536);
  for (size_t v = 0; v < values.size(); ++v) values[v] = uint16_t(v);
  for (uint64_t first : {uint64_t(0), uint64_t(37)}) {
    std::vector<double> sum(values.size(), 0.0);
    std::vector<uint8_t> frame(values.size());
    for (uint64_t f = first; f < first + 64; ++f) {
      dither_to_8_bits(values, 42, f, frame);
      for (size_t i = 0; i < values.size(); ++i) sum[i] += frame[i];
    }
    double worst = 0;
    for (size_t i = 0; i < values.size(); ++i) worst = std::max(worst, std::abs(sum[i] / 64 - values[i] / 257.0));
    EXPECT_LE(worst, 1.0 / 64) << "from frame " << first;
    EXPECT_LT(worst, 0.02);
  }
}

TEST(Dither, FramesComeBackFromTheSeedAndChangeFromFrameToFrame) {
  std::vector<uint16_t> grey(4096, uint16_t(128 * 257 + 100));  // between levels 128 and 129
  std::vector<uint8_t> a(grey.size()), b(grey.size()), next(grey.size()), other(grey.size());
  dither_to_8_bits(grey, 7, 3, a);
  dither_to_8_bits(grey, 7, 3, b);
  dither_to_8_bits(grey, 7, 4, next);
  dither_to_8_bits(grey, 8, 3, other);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, next);
  EXPECT_NE(a, other);
  size_t up = 0;
  for (uint8_t v : a) {
    EXPECT_TRUE(v == 128 || v == 129);
    up += v == 129;
  }
  // A spatial pattern, not a flat field: about 100/257 of the pixels round up.
  EXPECT_NEAR(double(up) / double(a.size()), 100.0 / 257, 0.03);
  // An exact 8-bit level stays exactly itself in every frame.
  std::vector<uint16_t> exact(16, uint16_t(200 * 257));
  std::vector<uint8_t> shown(exact.size());
  for (uint64_t f = 0; f < 64; ++f) {
    dither_to_8_bits(exact, 7, f, shown);
    for (uint8_t v : shown) EXPECT_EQ(v, 200);
  }
}

}  // namespace
}  // namespace countershade
