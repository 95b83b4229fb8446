// The lightness composition's fast paths against the scalar colour functions they must equal.

#include "enhance/lightness.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "test_util.h"

namespace countershade {
namespace {

// The vectorised conversion (decoding table, cube root) gives the scalar function's values bit
// for bit, for exact codes of 8 and 16 bits and for values that are not codes or out of range;
// so does its plane of L* as floats.
TEST(Lightness, DisplayToLabEqualsThePixelFunction) {
  testing::with_and_without_avx512([] {
    std::mt19937 random(3);
    for (int bits : {8, 16}) {
      const float levels = float((1u << bits) - 1u);
      Image image(131, 7, 3);  // an odd size: the vector blocks and their remainders
      std::uniform_int_distribution<int> code(0, int(levels));
      for (float& v : image.pixels) v = float(code(random)) / levels;
      image.pixels[5] = 0.123456f;  // not a code: its block is decoded directly
      image.pixels[400] = -0.0f;    // the code 0
      image.pixels[1000] = 1.5f;    // out of range: decoded directly
      image.pixels[2000] = -0.25f;
      for (const auto& encoding : {DisplayEncoding::srgb(), DisplayEncoding::gamma(2.2)}) {
        PixelVector lightness;
        LabPixels lab = display_to_lab(image, encoding, bits, &lightness);
        ASSERT_EQ(lightness.size(), lab.size());
        for (size_t i = 0; i < lab.size(); ++i) {
          const Lab expected = display_pixel_to_lab(&image.pixels[3 * i], encoding);
          ASSERT_EQ(lightness[i], float(expected.L)) << i;
          ASSERT_EQ(lab[i].L, expected.L) << i;
          ASSERT_EQ(lab[i].a, expected.a) << i;
          ASSERT_EQ(lab[i].b, expected.b) << i;
        }
        // The mean L* alone (the mean hold measures it once per offset it tries): the same sum.
        double sum = 0;
        for (size_t i = 0; i < lab.size(); ++i)
          sum += display_pixel_to_lab(&image.pixels[3 * i], encoding).L;
        EXPECT_EQ(mean_display_lightness(image, encoding, bits), sum / double(lab.size()));
      }
    }
  });
}

// The cube root is within a few ulp of the correctly rounded one over its whole range.
TEST(Lightness, CubeRootIsAccurate) {
  std::mt19937_64 random(4);
  std::uniform_real_distribution<double> exponent(-60.0, 30.0);
  for (int i = 0; i < 200000; ++i) {
    const double t = std::exp2(exponent(random));
    ASSERT_NEAR(color_constants::cube_root(t), std::cbrt(t),
                8 * std::abs(std::nextafter(std::cbrt(t), 0.0) - std::cbrt(t)))
        << t;
  }
}

// The vectorised composition gives the scalar colour functions' result, quantised exactly like a
// written stimulus, for random colours and changes (clipping included): eight pixels at a time
// where the processor has AVX-512, four at a time, and one at a time at the ends of blocks.
void expect_compose_equals_the_scalar_definition() {
  std::mt19937 random(5);
  Image display(97, 5, 3);
  std::uniform_int_distribution<int> code(0, 255);
  for (float& v : display.pixels) v = float(code(random)) / 255.0f;
  auto view = make_image_view(display, {}, DisplayEncoding::srgb(), 8);
  LightnessChange change;
  std::normal_distribution<double> delta(0.0, 20.0);
  for (size_t i = 0; i < view->lab.size(); ++i)
    change.amount.push_back(i % 7 == 0 ? 0.0 : delta(random));
  for (double lambda : {0.0, 0.3, 1.0, 3.0}) {
    Composed out = compose_lightness(*view, change, lambda);
    size_t clipped = 0;
    for (size_t i = 0; i < view->lab.size(); ++i) {
      const double d = lambda * change.amount[i];
      if (d == 0.0) {
        for (int c = 0; c < 3; ++c)
          ASSERT_EQ(out.display.pixels[3 * i + c], view->display.pixels[3 * i + c]);
        continue;
      }
      const double target = view->lab[i].L + d;
      const glm::dvec3 rgb = lab_to_linear_rgb(with_lightness(view->lab[i], target));
      bool clip = target < 0.0 || target > 100.0;
      for (int c = 0; c < 3; ++c) {
        clip |= rgb[c] < -1e-9 || rgb[c] > 1.0 + 1e-9;
        const float expected =
            float(quantize(float(view->encoding.encode(std::clamp(rgb[c], 0.0, 1.0))), 8)) / 255.0f;
        ASSERT_EQ(out.display.pixels[3 * i + c], expected) << i << " " << c << " λ " << lambda;
      }
      clipped += clip;
    }
    EXPECT_EQ(out.clipped_pixels, clipped) << lambda;
  }
}

TEST(Lightness, ComposeEqualsTheScalarDefinition) {
  testing::with_and_without_avx512(expect_compose_equals_the_scalar_definition);
}

// A detail change gives the bits of the scaled change whose amount is the stored difference
// S − smooth (S: the view's signal lightness), and lists its smooth plane as an auxiliary image.
TEST(Lightness, DetailChangeEqualsTheStoredDifference) {
  std::mt19937 random(6);
  Image display(53, 9, 3);
  std::uniform_int_distribution<int> code(0, 255);
  for (float& v : display.pixels) v = float(code(random)) / 255.0f;
  auto view = make_image_view(display, {}, DisplayEncoding::srgb(), 8);
  const std::span<const float> signal = view_signal_lightness(*view);
  LightnessChange detail, stored;
  detail.kind = LightnessChange::Kind::detail;
  detail.factor = stored.factor = 1.7;
  std::uniform_real_distribution<float> smooth(0.0f, 100.0f);
  for (size_t i = 0; i < signal.size(); ++i) {
    detail.smooth.push_back(i % 5 == 0 ? signal[i] : smooth(random));  // Δ = 0 on every fifth pixel
    stored.amount.push_back(double(signal[i]) - double(detail.smooth[i]));
  }
  for (double lambda : {0.0, 0.5, 2.0}) {
    const Composed a = compose_lightness(*view, detail, lambda),
                   b = compose_lightness(*view, stored, lambda);
    ASSERT_EQ(a.display.pixels, b.display.pixels) << lambda;
    EXPECT_EQ(a.clipped_pixels, b.clipped_pixels) << lambda;
  }
  const LightnessPrepared prepared(view, detail, {});
  const auto auxiliary = prepared.auxiliary();
  ASSERT_EQ(auxiliary.size(), 1u);
  EXPECT_EQ(auxiliary[0].first, "lightness_blurred");
  EXPECT_TRUE(
      std::equal(detail.smooth.begin(), detail.smooth.end(), auxiliary[0].second.pixels.begin()));
}

}  // namespace
}  // namespace countershade
