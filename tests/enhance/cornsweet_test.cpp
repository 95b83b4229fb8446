#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "enhance/cornsweet_profile.h"
#include "enhance/lightness.h"
#include "enhance/registry.h"
#include "enhance/view_plan.h"
#include "render/ray_tracer.h"
#include "render/scene_loader.h"
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
    double actual =
        display_pixel_to_lab(&out.display.pixels[3 * i], view.encoding).L - view.lab[i].L;
    EXPECT_NEAR(actual, expected, 1e-3) << x;
  }
  EXPECT_EQ(prepare_method("cornsweet", shared, o)->compose(0.0).display.pixels,
            view.display.pixels);
}

// The lightness literature's profile (Boyaci et al. 2007; stimupy): within w of the edge
// v(x) = v_plateau + (1 − x/w)^a·(v_edge − v_plateau), x the distance from the edge counted from
// the pixel on each side of it, the plateau beyond. Every pixel of a 1-D profile, before
// quantisation, and the edge pixels at the edge values themselves (the literature's extremes).
TEST(Cornsweet, PowerProfileFollowsTheFormulaAtEveryPixel) {
  const int width = 64;
  const double w = 9.5, a = 2.75, plateau = 50, dark_edge = 38, bright_edge = 66;
  CornsweetProfile profile;
  profile.power = true;
  profile.width = w;
  profile.exponent = a;
  profile.dark = dark_edge - plateau;
  profile.bright = bright_edge - plateau;
  const PixelDoubles got = cornsweet_image_profile(profile, width, 1);
  for (int column = 0; column < width; ++column) {
    const bool right = column >= width / 2;
    const double x = right ? column - width / 2 : width / 2 - 1 - column;  // 0 beside the edge
    const double edge = right ? bright_edge : dark_edge;
    const double v = x < w ? plateau + std::pow(1 - x / w, a) * (edge - plateau) : plateau;
    EXPECT_NEAR(plateau + got[size_t(column)], v, 1e-9) << column;
  }
  EXPECT_EQ(plateau + got[width / 2 - 1], dark_edge);
  EXPECT_EQ(plateau + got[width / 2], bright_edge);
  EXPECT_EQ(got[0], 0.0);  // the plateau, more than w from the edge
}

// Through the method on a uniform field at the plateau's L*: the edge values are given in L* as
// the literature gives them, λ = 1 draws them, and the pixels beside the edge reach them (within
// 16-bit quantisation); beyond w the field is untouched.
TEST(Cornsweet, PowerProfileReachesTheEdgeValuesOnAUniformField) {
  const Image grey(40, 4, 3, 0.5f);
  auto shared = make_image_view(grey, {}, DisplayEncoding::srgb(), 16);
  const View& view = *shared;
  const double plateau = view.lab[0].L;
  const nlohmann::json o = {{"profile", "power"},
                            {"sigma_px", 6.0},
                            {"edges", {plateau - 10, plateau + 12}},
                            {"plateau", plateau}};
  Composed out = prepare_method("cornsweet", shared, o)->compose(1.0);
  auto lightness = [&](int x) {
    return display_pixel_to_lab(&out.display.pixels[3 * size_t(40 + x)], view.encoding).L;
  };
  EXPECT_NEAR(lightness(19), plateau - 10, 2e-3);
  EXPECT_NEAR(lightness(20), plateau + 12, 2e-3);
  EXPECT_NEAR(lightness(22), plateau + 12 * std::pow(1 - 2 / 6.0, 2.75), 2e-3);
  EXPECT_NEAR(lightness(2), plateau, 2e-3);
  EXPECT_NEAR(lightness(37), plateau, 2e-3);
  // Bad parameters, each named.
  auto refused = [&](nlohmann::json bad, const std::string& key) {
    const std::string message =
        testing::input_error_of([&] { prepare_method("cornsweet", shared, bad); });
    EXPECT_NE(message.find(key), std::string::npos) << message;
  };
  refused({{"profile", "power"}, {"sigma_px", 6.0}, {"edges", {40, 60}}}, "plateau");
  refused({{"profile", "power"}, {"sigma_px", 6.0}, {"edges", {40}}, {"plateau", 50}}, "edges");
  refused({{"profile", "power"}, {"sigma_px", 6.0}, {"edges", {40, 160}}, {"plateau", 50}},
          "edges");
  refused({{"profile", "power"},
           {"sigma_px", 6.0},
           {"edges", {40, 60}},
           {"plateau", 50},
           {"amplitude", 3}},
          "amplitude");
  refused({{"profile", "power"}, {"sigma_px", 6.0}, {"exponent", -1}}, "exponent");
  refused({{"profile", "square"}, {"sigma_px", 6.0}}, "profile");
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
  nlohmann::json o = {{"mode", "surface"},
                      {"sigma", 0.1},
                      {"edge_point", {0, 0.5, 0.5}},  // the top/front edge
                      {"edge_direction", {1, 0, 0}},
                      {"bright_normal", {0, 1, 0}}};
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
