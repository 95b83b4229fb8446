#include "enhance/usm2d.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/gaussian.h"

namespace countershade {
namespace {

// A grey step edge as an external image view.
View step_view(float dark, float light) {
  Image img(64, 16, 3);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = x < 32 ? dark : light;
  return make_image_view(img, {}, DisplayEncoding::srgb(), 8);
}

MethodOptions sigma_px(double s) {
  MethodOptions o;
  o.sigma_px = s;
  return o;
}

TEST(Usm2d, LambdaZeroAndFlatImagesAreUnchanged) {
  View edge = step_view(0.3f, 0.7f);
  auto prepared = find_method("usm2d")->prepare(edge, sigma_px(4));
  EXPECT_EQ(prepared->compose(0.0).display.pixels, edge.display.pixels);
  View flat = step_view(0.5f, 0.5f);
  EXPECT_EQ(find_method("usm2d")->prepare(flat, sigma_px(4))->compose(2.0).display.pixels, flat.display.pixels);
}

TEST(Usm2d, ComposesLambdaTimesLightnessMinusItsBlur) {
  View edge = step_view(0.3f, 0.7f);
  const double lambda = 0.7, sigma = 4.0;
  Composed out = find_method("usm2d")->prepare(edge, sigma_px(sigma))->compose(lambda);
  std::vector<float> L(edge.lab.size()), blurred(L.size());
  for (size_t i = 0; i < L.size(); ++i) L[i] = float(edge.lab[i].L);
  gaussian_blur_exact(L.data(), blurred.data(), 64, 16, sigma);
  for (size_t i = 0; i < L.size(); ++i) {
    double expected = L[i] + lambda * (L[i] - blurred[i]);
    double actual = display_pixel_to_lab(&out.display.pixels[3 * i], edge.encoding).L;
    EXPECT_NEAR(actual, expected, 0.05) << i;  // the fast blur is within 1e-3 of the L* range
  }
  // Overshoot on the light side, undershoot on the dark side of the edge.
  EXPECT_GT(display_pixel_to_lab(&out.display.pixels[3 * (8 * 64 + 33)], edge.encoding).L, edge.lab[8 * 64 + 33].L + 1);
  EXPECT_LT(display_pixel_to_lab(&out.display.pixels[3 * (8 * 64 + 30)], edge.encoding).L, edge.lab[8 * 64 + 30].L - 1);
}

TEST(Usm2d, WidthOptionsAreExclusiveAndChecked) {
  const EnhancementMethod* m = find_method("usm2d");
  MethodOptions both = sigma_px(2);
  both.kernel_percent = 3;
  EXPECT_THROW(m->validate(both), InputError);
  EXPECT_THROW(m->validate(sigma_px(-1)), InputError);
  MethodOptions percent;
  percent.sigma_percent = 1.0;
  EXPECT_NO_THROW(m->validate(percent));
  EXPECT_DOUBLE_EQ(image_sigma_px(percent, 300, 400), 5.0);  // 1% of a 500 px diagonal
  MethodOptions kernel;
  kernel.kernel_percent = 4.0;
  EXPECT_DOUBLE_EQ(image_sigma_px(kernel, 300, 400), 5.0);  // K = 20 px, σ = K/4
}

}  // namespace
}  // namespace countershade
