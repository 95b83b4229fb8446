// Image-space filters of a rendered view take their detail from the render before it was
// quantised to code values: a gain must not turn the steps of an 8-bit gradient into contours.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "enhance/lightness.h"
#include "enhance/registry.h"
#include "enhance/view.h"
#include "enhance/view_plan.h"
#include "render/scene_loader.h"
#include "test_util.h"

namespace countershade {
namespace {

// A wall seen head on under a point light close to it: a smooth gradient over the whole image,
// spanning many 8-bit codes, with no edge, texture or shadow. One sample per pixel at its centre
// would do; a few jittered ones change nothing that matters here.
constexpr const char* kLitWall = R"({
  "version": 1,
  "camera": {"eye": [0, 0, 10], "target": [0, 0, 0], "projection": "orthographic", "height_world": 6,
             "width": 160, "height": 120},
  "render": {"spp": 4, "seed": 3},
  "objects": [{"name": "wall", "shape": {"type": "plane", "size": 20, "subdivisions": 8},
               "transform": {"rotate": [90, 0, 0]}, "material": {"albedo": 0.8}}],
  "lights": [{"type": "point", "position": [-2.5, 1.5, 4.0], "intensity": 9}]
})";

std::shared_ptr<const View> lit_wall(const testing::TempDir& dir) {
  return render_view(
      std::make_shared<Scene>(load_scene(testing::write_file(dir / "wall.json", kLitWall))));
}

TEST(SignalLightness, IsTheLightnessOfTheRenderBeforeQuantisation) {
  testing::TempDir dir;
  const auto view = lit_wall(dir);
  const std::span<const float> signal = view_signal_lightness(*view);
  const std::vector<float> quantised = view_lightness(*view);
  EXPECT_EQ(view_signal_lightness(*view).data(), signal.data());  // made once, kept by the view
  ASSERT_EQ(signal.size(), quantised.size());
  double largest = 0;
  size_t off_code = 0;
  for (size_t i = 0; i < signal.size(); ++i) {
    const float* c = &view->render.radiance.pixels[3 * i];
    EXPECT_NEAR(signal[i], cielab_lightness(display_luminance({c[0], c[1], c[2]}, Exposure{})),
                1e-4)
        << i;
    largest = std::max(largest, std::abs(double(signal[i]) - quantised[i]));
    off_code += signal[i] != quantised[i];
  }
  EXPECT_LT(largest, 0.5);                 // half an 8-bit step of sRGB is below 0.5 L* above black
  EXPECT_GT(off_code, signal.size() / 2);  // and the two planes do differ
  // A view read from an image file has nothing before its codes.
  const auto image = make_image_view(view->display, {}, view->encoding, 8);
  const std::span<const float> image_signal = view_signal_lightness(*image);
  EXPECT_EQ(std::vector<float>(image_signal.begin(), image_signal.end()), view_lightness(*image));
}

// The largest change of a code value (any channel) between the plain and the enhanced wall, away
// from the image's border. Enhancing the quantised L* instead of the render's adds λ times the
// quantisation's sawtooth (up to ±½ step): two and more codes at λ = 3.
int largest_code_change(const View& view, const Composed& enhanced, int margin) {
  int largest = 0;
  for (int y = margin; y < view.height() - margin; ++y)
    for (int x = margin; x < view.width() - margin; ++x)
      for (int c = 0; c < 3; ++c) {
        const size_t i = 3 * (size_t(y) * view.width() + x) + c;
        const int before = int(std::lround(view.display.pixels[i] * 255.0f));
        const int after = int(std::lround(enhanced.display.pixels[i] * 255.0f));
        largest = std::max(largest, std::abs(after - before));
      }
  return largest;
}

TEST(SignalLightness, AGainDoesNotTurnEightBitStepsIntoContours) {
  testing::TempDir dir;
  const auto view = lit_wall(dir);
  const nlohmann::json usm2d = {{"sigma_px", 4}};
  const nlohmann::json post = {{"mode", "post"}, {"filter", "unsharp"}, {"sigma", 4}};
  for (const auto& [method, parameters] :
       {std::pair{"usm2d", usm2d}, std::pair{"texture-filter", post}}) {
    const Composed enhanced = prepare_method(method, view, parameters)->compose(3.0);
    // The gradient's own detail at σ = 4 px is far below a step: nothing may move by two.
    EXPECT_LE(largest_code_change(*view, enhanced, 12), 1) << method;
  }
}

}  // namespace
}  // namespace countershade
