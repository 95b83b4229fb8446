#include <gtest/gtest.h>

#include "core/error.h"
#include "core/gaussian.h"
#include "enhance/image_width.h"
#include "enhance/lightness.h"
#include "enhance/registry.h"
#include "enhance/view_plan.h"
#include "test_util.h"

namespace countershade {
namespace {

// A grey step edge as an external image view, at 16 bits so that the quantisation of the composed
// stimulus (half a level: 0.002 L*) stays far below the tolerances.
std::shared_ptr<const View> step_view(float dark, float light) {
  Image img(64, 16, 3);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = x < 32 ? dark : light;
  return make_image_view(img, {}, DisplayEncoding::srgb(), 16);
}

nlohmann::json sigma_px(double s) { return {{"sigma_px", s}}; }

std::shared_ptr<const MethodParameters> parse(const nlohmann::json& j) {
  return method_named("usm2d", "test").parse(ParameterBag::from_json(j, "exp.json", "methods[0]"));
}

TEST(Usm2d, LambdaZeroAndFlatImagesAreUnchanged) {
  auto edge = step_view(0.3f, 0.7f);
  auto prepared = prepare_method("usm2d", edge, sigma_px(4));
  EXPECT_EQ(prepared->compose(0.0).display.pixels, edge->display.pixels);
  auto flat = step_view(0.5f, 0.5f);
  EXPECT_EQ(prepare_method("usm2d", flat, sigma_px(4))->compose(2.0).display.pixels,
            flat->display.pixels);
}

TEST(Usm2d, ComposesLambdaTimesLightnessMinusItsBlur) {
  auto shared = step_view(0.3f, 0.7f);
  const View& edge = *shared;
  const double lambda = 0.7, sigma = 4.0;
  Composed out = prepare_method("usm2d", shared, sigma_px(sigma))->compose(lambda);
  std::vector<float> L(edge.lab.size()), blurred(L.size());
  for (size_t i = 0; i < L.size(); ++i) L[i] = float(edge.lab[i].L);
  gaussian_blur_exact(L.data(), blurred.data(), 64, 16, sigma);
  for (size_t i = 0; i < L.size(); ++i) {
    double expected = L[i] + lambda * (L[i] - blurred[i]);
    double actual = display_pixel_to_lab(&out.display.pixels[3 * i], edge.encoding).L;
    EXPECT_NEAR(actual, expected, 0.05) << i;  // the fast blur is within 1e-3 of the L* range
  }
  // Overshoot on the light side, undershoot on the dark side of the edge.
  EXPECT_GT(display_pixel_to_lab(&out.display.pixels[3 * (8 * 64 + 33)], edge.encoding).L,
            edge.lab[8 * 64 + 33].L + 1);
  EXPECT_LT(display_pixel_to_lab(&out.display.pixels[3 * (8 * 64 + 30)], edge.encoding).L,
            edge.lab[8 * 64 + 30].L - 1);
}

TEST(Usm2d, WidthOptionsAreExclusiveAndChecked) {
  EXPECT_THROW(parse({{"sigma_px", 2}, {"kernel_percent", 3}}), InputError);
  EXPECT_THROW(parse(sigma_px(-1)), InputError);
  EXPECT_THROW(parse(nlohmann::json::object()), InputError);
  EXPECT_NO_THROW(parse({{"sigma_percent", 1.0}}));
  ImageWidth percent, kernel;
  percent.sigma_percent = 1.0;
  EXPECT_DOUBLE_EQ(percent.sigma_px_for(300, 400), 5.0);  // 1% of a 500 px diagonal
  kernel.kernel_percent = 4.0;
  EXPECT_DOUBLE_EQ(kernel.sigma_px_for(300, 400), 5.0);  // K = 20 px, σ = K/4
  // "5%" on the command line is the same kernel.
  auto text = method_named("usm2d", "test").parse(ParameterBag::from_arguments({"--kernel", "4%"}));
  EXPECT_NO_THROW(text.get());
}

// usm2d works on L* by definition; a `space` key used to be accepted and ignored, so a "usm2d-lab"
// folder held copies of the RGB images. It is now refused, saying why.
TEST(Usm2d, HasNoColourSpaceToChoose) {
  std::string message = testing::input_error_of([] { parse({{"sigma_px", 2}, {"space", "lab"}}); });
  EXPECT_NE(message.find("exp.json: methods[0].space"), std::string::npos) << message;
  EXPECT_NE(message.find("lightness"), std::string::npos) << message;
}

}  // namespace
}  // namespace countershade
