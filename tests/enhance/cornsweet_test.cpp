#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "enhance/lightness.h"
#include "enhance/registry.h"
#include "render/ray_tracer.h"
#include "test_util.h"

namespace countershade {
namespace {

// On a uniform field the image mode draws exactly ΔL* = ±λ·A·exp(−|d|/w) across the centre line.
TEST(Cornsweet, ImageProfileFollowsTheDefinition) {
  auto shared = make_image_view(Image(101, 8, 3, 0.45f), {}, DisplayEncoding::srgb(), 16);
  const View& view = *shared;
  const nlohmann::json o = {{"sigma_px", 6.0}, {"amplitude", 4.0}};
  const double lambda = 1.5;
  Composed out = prepare_method("cornsweet", shared, o)->compose(lambda);
  EXPECT_EQ(out.clipped_pixels, 0u);
  for (int x = 0; x < 101; ++x) {
    size_t i = size_t(3 * 101 + x);
    double d = (x + 0.5) - 50.5;
    double expected = (d > 0 ? 1 : -1) * lambda * 4.0 * std::exp(-std::abs(d) / 6.0);
    double actual = display_pixel_to_lab(&out.display.pixels[3 * i], view.encoding).L - view.lab[i].L;
    EXPECT_NEAR(actual, expected, 1e-3) << x;
  }
  EXPECT_EQ(prepare_method("cornsweet", shared, o)->compose(0.0).display.pixels, view.display.pixels);
}

TEST(Cornsweet, SurfaceProfileBrightensOneFaceAndDarkensTheOther) {
  testing::TempDir dir;
  auto scene = std::make_shared<Scene>(load_scene(testing::write_file(dir / "s.json", R"({
    "version": 1,
    "camera": {"eye": [0, 3, 3], "target": [0, 0, 0], "projection": "orthographic", "height_world": 2.2,
               "width": 80, "height": 80},
    "render": {"spp": 1},
    "objects": [{"shape": {"type": "box", "size": [1, 1, 1], "subdivisions": 8}, "material": {"albedo": 0.5}}],
    "lights": [{"type": "ambient", "radiance": 0.6}]
  })")));
  ViewOptions vo;
  vo.bits = 16;
  nlohmann::json o = {{"mode", "surface"}, {"sigma", 0.1}, {"edge_point", {0, 0.5, 0.5}},  // the top/front edge
                      {"edge_direction", {1, 0, 0}}, {"bright_normal", {0, 1, 0}}};
  auto shared = render_view(scene, plan_for("cornsweet", o, 1.0), vo);
  const View& view = *shared;
  Composed out = prepare_method("cornsweet", shared, o)->compose(1.0);
  const GBuffer& g = view.render.gbuffer;
  int top = 0, front = 0;
  for (size_t i = 0; i < g.object.size(); ++i) {
    if (g.object[i] < 0) continue;
    double dl = display_pixel_to_lab(&out.display.pixels[3 * i], view.encoding).L - view.lab[i].L;
    if (g.normal[i].y > 0.9f) {
      EXPECT_GE(dl, -1e-3);
      top += dl > 0.5;
    } else if (g.normal[i].z > 0.9f) {
      EXPECT_LE(dl, 1e-3);
      front += dl < -0.5;
    }
  }
  EXPECT_GT(top, 20);
  EXPECT_GT(front, 20);
  o.erase("sigma");
  EXPECT_THROW(prepare_method("cornsweet", shared, o), InputError);
  o["sigma_px"] = 4;  // the image mode's width
  EXPECT_THROW(prepare_method("cornsweet", shared, o), InputError);
}

}  // namespace
}  // namespace countershade
