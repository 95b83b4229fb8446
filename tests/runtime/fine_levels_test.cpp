// The 16-bit output paths' definitions, checked against independent arithmetic: the nearest
// 10-bit level, and the dither whose mean over 64 frames is the 16-bit value.

#include "runtime/fine_levels.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

namespace countershade::runtime {

namespace {

TEST(FineLevels, TheTenBitLevelIsTheNearestOneForEverySixteenBitCode) {
  for (uint32_t v = 0; v <= 65535; ++v) {
    const double exact = double(v) * 1023.0 / 65535.0;
    const uint32_t level = ten_bit_level(v);
    ASSERT_LE(std::abs(double(level) - exact), 0.5) << v;
    ASSERT_LE(level, 1023u);
  }
  EXPECT_EQ(ten_bit_level(65535), 1023u);
  EXPECT_EQ(ten_bit_level(0), 0u);
}

// Over any 64 consecutive frames, each pixel's mean 8-bit level is within 1/64 of its 16-bit
// value in 8-bit units (the bound is 0.02), for every code, at pixels and starting frames
// spread at random.
TEST(FineLevels, TheDithersMeanOverSixtyFourFramesIsTheSixteenBitValue) {
  std::mt19937 random(11);
  double worst = 0;
  for (uint32_t v = 0; v <= 65535; ++v) {
    const uint32_t x = random() % 4096, y = random() % 4096, start = random() % 100000,
                   seed = random();
    int sum = 0;
    for (uint32_t f = start; f < start + 64; ++f)
      sum += int(dither_level(v, dither_threshold(x, y, f, seed)));
    const double error = std::abs(sum / 64.0 - double(v) * 255.0 / 65535.0);
    worst = std::max(worst, error);
    ASSERT_LT(error, 0.02) << "code " << v << " at " << x << "," << y;
  }
  EXPECT_LE(worst, 1.0 / 64 + 1e-12);
}

TEST(FineLevels, TheDitherShowsOnlyTheTwoLevelsAroundTheValue) {
  for (uint32_t v = 0; v <= 65535; v += 7)
    for (uint32_t f = 0; f < 8; ++f) {
      const double exact = double(v) * 255.0 / 65535.0;
      const uint32_t level = dither_level(v, dither_threshold(v % 97, v % 89, f, 3));
      ASSERT_TRUE(level == uint32_t(std::floor(exact)) || level == uint32_t(std::ceil(exact))) << v;
    }
  // An exact 8-bit level (a multiple of 257) stays itself in every frame.
  for (uint32_t level = 0; level <= 255; ++level)
    for (uint32_t f = 0; f < 64; ++f)
      ASSERT_EQ(dither_level(level * 257, dither_threshold(level, 3, f, 9)), level);
}

// Thresholds spread evenly over [0, 65535) across pixels (no visible pattern of a few values),
// each frame's pattern differs from the last, and the seed changes the pattern.
TEST(FineLevels, TheDitherPatternIsSpatiallyEvenAndChangesEveryFrameAndWithTheSeed) {
  constexpr int kBins = 16, kSide = 256;
  std::vector<int> bins(kBins, 0);
  int same_as_last = 0, same_other_seed = 0;
  for (uint32_t y = 0; y < kSide; ++y)
    for (uint32_t x = 0; x < kSide; ++x) {
      const uint32_t t = dither_threshold(x, y, 5, 42);
      ASSERT_LT(t, 65535u);
      ++bins[t * kBins / 65535];
      same_as_last += t == dither_threshold(x, y, 4, 42);
      same_other_seed += t == dither_threshold(x, y, 5, 43);
    }
  double chi2 = 0;
  const double expected = double(kSide * kSide) / kBins;
  for (int b : bins) chi2 += (b - expected) * (b - expected) / expected;
  EXPECT_LT(chi2, 37.7);  // χ² with 15 degrees of freedom, p = 0.001
  EXPECT_LT(same_as_last, kSide * kSide / 1000);
  EXPECT_LT(same_other_seed, kSide * kSide / 1000);
}

// The boost table as Psychtoolbox's CreatePseudoGrayLUT lists it (slots counted from 0), written
// out here apart from the masks in fine_levels.h.
constexpr int kBoost[16][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {1, 0, 0},
                               {1, 0, 0}, {1, 0, 1}, {1, 0, 1}, {0, 1, 0}, {0, 1, 0}, {0, 1, 1},
                               {0, 1, 1}, {0, 1, 1}, {1, 1, 0}, {1, 1, 0}};

// Bit stealing: Psychtoolbox's table, its 1786 levels, and every 16-bit grey value shown within
// 0.14 + 1/32 of a level when the guns weigh 0.30, 0.59 and 0.11 (the weights the table is built
// for): the worst slot is 4 (a quarter of a step shown as blue's 0.11), and the index's rounding
// adds half a sixteenth. The nearest 8-bit level can be half a level off.
TEST(FineLevels, PseudoGreyIsPsychtoolboxsTableAndSplitsEachLevelInSeven) {
  const uint32_t masks[3] = {kPseudoGreyRed, kPseudoGreyGreen, kPseudoGreyBlue};
  for (uint32_t slot = 0; slot < 16; ++slot)
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(int((masks[c] >> slot) & 1u), kBoost[slot][c]) << slot << " " << c;
  std::set<uint32_t> triplets;
  double worst = 0, previous = -1;
  bool monotonic = true;
  for (uint32_t v = 0; v <= 65535; ++v) {
    const uint32_t r = pseudo_grey_level(v, kPseudoGreyRed),
                   g = pseudo_grey_level(v, kPseudoGreyGreen),
                   b = pseudo_grey_level(v, kPseudoGreyBlue);
    triplets.insert(r << 16 | g << 8 | b);
    const double shown = 0.30 * r + 0.59 * g + 0.11 * b;
    worst = std::max(worst, std::abs(shown - v * 255.0 / 65535.0));
    monotonic = monotonic && shown >= previous;
    previous = shown;
  }
  EXPECT_EQ(triplets.size(), 1786u);
  EXPECT_TRUE(monotonic);
  EXPECT_LE(worst, 0.14 + 1.0 / 32);
  EXPECT_GT(worst, 0.14);
  EXPECT_EQ(pseudo_grey_level(65535, kPseudoGreyGreen), 255u);
  EXPECT_EQ(pseudo_grey_level(257 * 77, kPseudoGreyRed), 77u);  // an 8-bit level is its own grey
}

TEST(FineLevels, OutputPathsParseByName) {
  EXPECT_TRUE(parse_output_path("auto")->automatic);
  EXPECT_EQ(parse_output_path("ten-bit")->path, OutputPath::ten_bit);
  EXPECT_EQ(parse_output_path("dither")->path, OutputPath::dither);
  EXPECT_EQ(parse_output_path("pseudo-grey")->path, OutputPath::pseudo_grey);
  EXPECT_FALSE(parse_output_path("pseudo-grey")->may_use_ten_bit());
  EXPECT_FALSE(parse_output_path("10bit"));
  EXPECT_STREQ(output_path_name(OutputPath::ten_bit), "ten-bit");
}

}  // namespace
}  // namespace countershade::runtime
