// A display's black level (the scene's "black_level"): radiance 0 shows as that share of full
// scale, every other value is lifted in proportion, and lightness is measured on the lifted image.

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "enhance/lightness.h"
#include "enhance/view.h"
#include "enhance/view_plan.h"
#include "render/scene_loader.h"
#include "test_util.h"

namespace countershade {
namespace {

// The lit cube on a black background, with a fixed sample count so that the radiance does not
// depend on the display.
std::shared_ptr<const View> cube_view(const testing::TempDir& dir, const std::string& display) {
  std::string text = testing::kLitCubeScene;
  const std::string from = R"("display": {"background": 0.18})";
  text.replace(text.find(from), from.size(), R"("display": {"background": 0)" + display + "}");
  auto scene = load_scene(testing::write_file(dir / "cube.json", text));
  scene.camera.width = 64;
  scene.camera.height = 48;
  return render_view(std::make_shared<Scene>(std::move(scene)));
}

TEST(BlackLevel, LiftsEveryChannelInProportionAndLightnessSeesIt) {
  testing::TempDir dir;
  const auto plain = cube_view(dir, ""), lifted = cube_view(dir, R"(, "black_level": 0.05)");
  ASSERT_EQ(plain->render.radiance.pixels, lifted->render.radiance.pixels);
  // The corner sees the background: linear 0.05, sRGB code 0.2478 (8-bit 63), L* 26.73.
  EXPECT_EQ(plain->display.pixels[0], 0.0f);
  EXPECT_NEAR(lifted->display.pixels[0] * 255.0, 63.0, 1e-3);
  EXPECT_NEAR(view_lightness(*lifted)[0], 26.65, 0.01);         // of code 63 as shown
  EXPECT_NEAR(view_signal_lightness(*lifted)[0], 26.73, 0.01);  // before quantisation
  // Every channel: 0.05 + 0.95·x of the plain display's linear value x, within a code.
  const DisplayEncoding srgb = DisplayEncoding::srgb();
  for (size_t i = 0; i < plain->display.pixels.size(); ++i) {
    const double x = srgb.decode(plain->display.pixels[i]),
                 y = srgb.decode(lifted->display.pixels[i]);
    ASSERT_NEAR(srgb.encode(0.05 + 0.95 * x), srgb.encode(y), 1.0 / 255) << i;
  }
}

TEST(BlackLevel, IsAShareOfFullScaleUpToAHalf) {
  testing::TempDir dir;
  const std::string error =
      testing::input_error_of([&] { cube_view(dir, R"(, "black_level": 0.6)"); });
  EXPECT_NE(error.find("black_level"), std::string::npos) << error;
}

}  // namespace
}  // namespace countershade
