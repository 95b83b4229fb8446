#include "enhance/usm3d.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <map>

#include "core/error.h"
#include "core/image.h"
#include "core/svg_plot.h"
#include "enhance/lightness.h"
#include "enhance/registry.h"
#include "enhance/view_plan.h"
#include "render/ray_tracer.h"
#include "render/scene_loader.h"
#include "test_util.h"

namespace countershade {
namespace {

struct Rendered {
  Scene scene;  // the view's scene, copied for the tests' convenience
  std::shared_ptr<const View> view;
};

nlohmann::json with_sigma(double sigma) { return {{"sigma", sigma}}; }

// Loads a scene from JSON text and renders its view for usm3d with each of `uses` (parameters).
Rendered render_test_view(const testing::TempDir& dir, const std::string& json,
                          const std::vector<nlohmann::json>& uses, int bits = 8) {
  Rendered r;
  r.scene = load_scene(testing::write_file(dir / "scene.json", json));
  ViewPlan plan;
  plan.max_abs_lambda = 3;
  for (const auto& use : uses) plan.add("usm3d", use);
  ViewOptions options;
  options.bits = bits;
  r.view = render_view(std::make_shared<Scene>(r.scene), plan, options);
  return r;
}

// The per-pixel contrast (amount) and gain of a prepared usm3d.
const LightnessChange& change_of(const PreparedEnhancement& prepared) {
  return dynamic_cast<const LightnessPrepared&>(prepared).change();
}

std::vector<uint8_t> bytes_of(const Image& display) {
  std::vector<uint8_t> out(display.pixels.size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = uint8_t(quantize(display.pixels[i], 8));
  return out;
}

nlohmann::json with_ring(double sigma) { return {{"sigma", sigma}, {"ring_samples", 3}}; }

SmoothingWidth width_of(double sigma) {
  SmoothingWidth w;
  w.sigma = sigma;
  return w;
}

const char* kTexturedCow = R"({
  "version": 1,
  "camera": {"eye": [1.4, 0.9, 1.6], "target": [0, 0.4, 0], "fov": 35, "width": 96, "height": 72},
  "render": {"spp": 2, "seed": 4},
  "display": {"background": 0.2},
  "objects": [
    {"shape": {"type": "plane", "size": 3, "subdivisions": 30}, "material": {"albedo": [0.5, 0.55, 0.6]}},
    {"mesh": "SPOT", "fit": true, "transform": {"rotate": [0, 235, 0]},
     "material": {"texture": "TEXTURE"}}
  ],
  "lights": [{"type": "directional", "direction": [0.5, 1, 0.7], "irradiance": 2.2},
             {"type": "ambient", "radiance": 0.2}]
})";

std::string textured_cow() {
  std::string s = kTexturedCow;
  s.replace(s.find("SPOT"), 4, testing::mesh_path("spot.obj").string());
  s.replace(s.find("TEXTURE"), 7, testing::mesh_path("spot_texture.png").string());
  return s;
}

TEST(Usm3d, LambdaZeroIsByteIdenticalToNone) {
  testing::TempDir dir;
  Rendered r = render_test_view(dir, textured_cow(), {with_sigma(0.1)});
  auto none = prepare_method("none", r.view, nlohmann::json::object())->compose(0.0);
  auto usm = prepare_method("usm3d", r.view, with_sigma(0.1));
  Composed zero = usm->compose(0.0);
  EXPECT_EQ(zero.display.pixels, none.display.pixels);  // exact floats, hence exact bytes
  EXPECT_EQ(zero.clipped_pixels, 0u);
  EXPECT_NE(bytes_of(usm->compose(1.0).display), bytes_of(none.display));
}

TEST(Usm3d, ConstantLightnessSurfaceIsUnchangedForEveryLambdaAndSigma) {
  testing::TempDir dir;
  // An orthographic view filled by a plane lit head-on: every vertex and pixel has the same
  // radiance.
  Rendered r = render_test_view(dir, R"({
    "version": 1,
    "camera": {"eye": [0, 5, 0], "target": [0, 0, 0], "up": [0, 0, -1], "projection": "orthographic",
               "height_world": 2, "width": 40, "height": 40},
    "render": {"spp": 4},
    "objects": [{"shape": {"type": "plane", "size": 4, "subdivisions": 24}, "material": {"albedo": [0.6, 0.4, 0.3]}}],
    "lights": [{"type": "directional", "direction": [0, 1, 0], "irradiance": 1.5}]
  })",
                                {with_ring(0.05), with_ring(0.5)});
  auto reference = bytes_of(r.view->display);
  for (double sigma : {0.05, 0.5})
    for (double lambda : {0.5, 3.0, -2.0}) {
      Composed out = prepare_method("usm3d", r.view, with_ring(sigma))->compose(lambda);
      EXPECT_EQ(bytes_of(out.display), reference) << sigma << " " << lambda;
      for (size_t i = 0; i < out.display.pixels.size(); ++i)
        ASSERT_NEAR(out.display.pixels[i], r.view->display.pixels[i], 1e-5);
    }
}

TEST(Usm3d, KeepsHueAndSaturationWhereNotClipped) {
  testing::TempDir dir;
  // 16-bit stimuli: the composed stimulus is code values, which round hue.
  Rendered r = render_test_view(dir, textured_cow(), {{{"sigma_fraction", 0.05}}}, 16);
  Composed out = prepare_method("usm3d", r.view, {{"sigma_fraction", 0.05}})->compose(2.5);
  const DisplayEncoding& enc = r.scene.display.encoding;
  int checked = 0;
  for (size_t i = 0; i < r.view->lab.size(); ++i) {
    const Lab& before = r.view->lab[i];
    Lab after = display_pixel_to_lab(&out.display.pixels[3 * i], enc);
    if (std::abs(after.L - before.L) < 1e-3) continue;
    // Clipped, or so dark (L* < 5) that the code values do not resolve hue.
    bool clipped = after.L <= 5.0 || after.L >= 99.99;
    for (int c = 0; c < 3; ++c)
      clipped |= out.display.pixels[3 * i + c] <= 0.0f || out.display.pixels[3 * i + c] >= 1.0f;
    double chroma = std::hypot(before.a, before.b);
    if (clipped || chroma < 2.0) continue;  // hue is undefined for neutral pixels
    // 16-bit code values move a* and b* by up to about 0.01: the tolerances allow for that.
    EXPECT_NEAR(std::atan2(after.b, after.a), std::atan2(before.b, before.a), 1e-3 + 0.01 / chroma)
        << i;
    EXPECT_NEAR(std::hypot(after.a, after.b) / after.L, chroma / before.L, 1e-3 + 0.01 / after.L)
        << i;
    ++checked;
  }
  EXPECT_GT(checked, 500);
}

// Ritschel et al.'s Fig. 4 claim: moving an occluder in front of a lit, shadowed wall leaves the
// wall's contrast signal where it was. The bar's own shadow falls beside the wall (grazing light).
std::string wall_scene(double bar_x) {
  return R"({
    "version": 1,
    "camera": {"eye": [0, 0, 6], "target": [0, 0, 0], "fov": 40, "width": 96, "height": 72},
    "render": {"spp": 4, "seed": 2},
    "objects": [
      {"name": "wall", "shape": {"type": "plane", "size": 4, "subdivisions": 60}, "transform": {"rotate": [90, 0, 0]},
       "material": {"albedo": 0.7}},
      {"name": "caster", "shape": {"type": "box", "size": [0.6, 0.6, 0.2]}, "transform": {"translate": [0.5, 0.5, 0.6]}},
      {"name": "bar", "shape": {"type": "box", "size": [0.2, 3, 0.2]}, "transform": {"translate": [)" +
         std::to_string(bar_x) + R"(, 0, 3]}, "material": {"albedo": 0.1}}
    ],
    "lights": [{"type": "directional", "direction": [1.2, 0.3, 1], "irradiance": 2.5},
               {"type": "ambient", "radiance": 0.15}]
  })";
}

TEST(Usm3d, ContrastSignalIsSceneCoherentUnderAMovingOccluder) {
  testing::TempDir dir_a, dir_b;
  const double sigma = 0.3, lambda = 2.0;
  Rendered a = render_test_view(dir_a, wall_scene(-1.0), {with_sigma(sigma)});
  Rendered b = render_test_view(dir_b, wall_scene(-0.4), {with_sigma(sigma)});
  auto prepared_a = prepare_method("usm3d", a.view, with_sigma(sigma));
  auto prepared_b = prepare_method("usm3d", b.view, with_sigma(sigma));
  const PixelDoubles& contrast_a = change_of(*prepared_a).amount;
  const PixelDoubles& contrast_b = change_of(*prepared_b).amount;
  Composed ea = prepared_a->compose(lambda);
  Composed eb = prepared_b->compose(lambda);
  const GBuffer& ga = a.view->render.gbuffer;
  const GBuffer& gb = b.view->render.gbuffer;
  // Wall pixels whose whole 3×3 neighbourhood is wall in both frames (no anti-aliasing overlap).
  auto wall_in_both = [&](int x, int y) {
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        int xx = std::clamp(x + dx, 0, ga.width - 1), yy = std::clamp(y + dy, 0, ga.height - 1);
        if (ga.object[ga.index(xx, yy)] != 0 || gb.object[gb.index(xx, yy)] != 0) return false;
      }
    return true;
  };
  // Distance (in pixels) to the bar in frame a, to find the wall around its silhouette.
  auto near_bar_in_a = [&](int x, int y) {
    for (int dx = -6; dx <= 6; ++dx) {
      int xx = std::clamp(x + dx, 0, ga.width - 1);
      if (ga.object[ga.index(xx, y)] == 2) return true;
    }
    return false;
  };
  int compared = 0, around_silhouette = 0;
  double largest_contrast = 0;
  for (int y = 0; y < ga.height; ++y)
    for (int x = 0; x < ga.width; ++x) {
      if (!wall_in_both(x, y)) continue;
      size_t i = ga.index(x, y);
      EXPECT_NEAR(contrast_a[i], contrast_b[i], 1e-4) << x << "," << y;
      largest_contrast = std::max(largest_contrast, std::abs(contrast_a[i]));
      ++compared;
      if (near_bar_in_a(x, y)) {
        ++around_silhouette;
        double delta_a =
            display_pixel_to_lab(&ea.display.pixels[3 * i], a.scene.display.encoding).L -
            a.view->lab[i].L;
        double delta_b =
            display_pixel_to_lab(&eb.display.pixels[3 * i], b.scene.display.encoding).L -
            b.view->lab[i].L;
        EXPECT_NEAR(delta_a, delta_b, 1e-3)
            << "the occluder changed the wall beside it at " << x << "," << y;
      }
    }
  EXPECT_GT(compared, 2000);
  EXPECT_GT(around_silhouette, 50);
  EXPECT_GT(largest_contrast, 5.0) << "the wall's shadow edge should carry a real contrast signal";
}

// Lightness profile down the image column that crosses the edge between a cube's front and top
// faces.
struct Profile {
  std::vector<double> offset, delta_L;  // pixels from the edge (negative: top face), L' - L
  double peak = 0, half_width = 0;      // on the front face
};

Profile cube_profile(const std::shared_ptr<const View>& shared, double sigma, double lambda) {
  const View& view = *shared;
  Composed out = prepare_method("usm3d", shared, with_sigma(sigma))->compose(lambda);
  EXPECT_EQ(out.clipped_pixels, 0u);
  const GBuffer& g = view.render.gbuffer;
  int x = g.width / 2, edge = -1;
  for (int y = 1; y < g.height; ++y)  // the first row whose normal faces the camera (front face)
    if (g.object[g.index(x, y)] == 0 && g.normal[g.index(x, y)].z > 0.9f &&
        g.normal[g.index(x, y - 1)].y > 0.9f)
      edge = y;
  EXPECT_GT(edge, 0);
  Profile p;
  for (int y = 0; y < g.height; ++y) {
    size_t i = g.index(x, y);
    if (g.object[i] != 0) continue;
    double d = display_pixel_to_lab(&out.display.pixels[3 * i], view.scene->display.encoding).L -
               view.lab[i].L;
    p.offset.push_back(y - edge);
    p.delta_L.push_back(d);
  }
  // Peak within the front face's upper part (its lower edge has a Cornsweet edge of its own),
  // then the distance at which the overshoot has fallen to half.
  size_t at = 0;
  for (size_t k = 0; k < p.offset.size(); ++k)
    if (p.offset[k] >= 0 && p.offset[k] <= 25 && p.delta_L[k] > p.peak) p.peak = p.delta_L[at = k];
  for (size_t k = at; k < p.offset.size(); ++k)
    if (p.delta_L[k] < 0.5 * p.peak) {
      p.half_width = p.offset[k];
      break;
    }
  return p;
}

TEST(Usm3d, CornsweetCubeProfileOvershootsAndScalesWithLambdaAndSigma) {
  testing::TempDir dir;
  Rendered r =
      render_test_view(dir, R"({
    "version": 1,
    "camera": {"eye": [0, 4, 4], "target": [0, 0, 0], "projection": "orthographic", "height_world": 2.6,
               "width": 160, "height": 160},
    "render": {"spp": 4},
    "display": {"background": 0.18},
    "objects": [{"name": "cube", "shape": {"type": "box", "size": [1.6, 1.6, 1.6], "subdivisions": 48},
                 "material": {"albedo": 0.5}}],
    "lights": [{"type": "directional", "direction": [0, 0.35, 1], "irradiance": 1.2},
               {"type": "ambient", "radiance": 0.2}]
  })",
                       {with_sigma(0.1), with_sigma(0.15), with_sigma(0.2), with_sigma(0.3)});
  // Amplitude grows linearly with λ.
  std::vector<double> lambdas = {0.5, 1.0, 2.0}, peaks;
  for (double l : lambdas) peaks.push_back(cube_profile(r.view, 0.15, l).peak);
  double mx = 0, my = 0;
  for (size_t i = 0; i < 3; ++i) mx += lambdas[i] / 3, my += peaks[i] / 3;
  double sxy = 0, sxx = 0, syy = 0;
  for (size_t i = 0; i < 3; ++i) {
    sxy += (lambdas[i] - mx) * (peaks[i] - my);
    sxx += (lambdas[i] - mx) * (lambdas[i] - mx);
    syy += (peaks[i] - my) * (peaks[i] - my);
  }
  EXPECT_GT(sxy * sxy / (sxx * syy), 0.99);
  EXPECT_GT(peaks[0], 1.0) << "a visible overshoot (ΔL* > 1) already at λ = 0.5";

  Profile narrow = cube_profile(r.view, 0.1, 1.0), wide = cube_profile(r.view, 0.3, 1.0);
  EXPECT_GT(wide.half_width, narrow.half_width + 2) << "the Cornsweet profile widens with σ";
  // Overshoot on the brighter front face, undershoot on the top face next to the edge.
  for (size_t k = 0; k < narrow.offset.size(); ++k) {
    if (narrow.offset[k] >= 1 && narrow.offset[k] <= 3) {
      EXPECT_GT(narrow.delta_L[k], 0.0);
    }
    if (narrow.offset[k] <= -2 && narrow.offset[k] >= -4) {
      EXPECT_LT(narrow.delta_L[k], 0.0);
    }
  }

  // The figure in docs/figures/ comes from here: COUNTERSHADE_FIGURE_DIR=docs/figures.
  if (const char* figures = std::getenv("COUNTERSHADE_FIGURE_DIR")) {
    LinePlot plot;
    plot.title = "3D unsharp masking of a grey cube: lightness change across the top/front edge";
    plot.x_label = "pixels from the edge (negative: top face, positive: front face)";
    plot.y_label = "ΔL* (enhanced − original)";
    size_t k = 0;
    for (double sigma : {0.1, 0.2, 0.3})
      for (double lambda : {1.0, 2.0}) {
        Profile p = cube_profile(r.view, sigma, lambda);
        char label[64];
        std::snprintf(label, sizeof label, "σ=%.1f λ=%.0f", sigma, lambda);
        plot.series.push_back({label, p.offset, p.delta_L, plot_color(k / 2), lambda == 1.0});
        ++k;
      }
    plot.write(std::filesystem::path(figures) / "cornsweet-cube-profile.svg");
  }
}

TEST(Usm3d, NothingLeaksBetweenDisconnectedObjects) {
  auto scene = [](double albedo_b) {
    return R"({
      "version": 1,
      "camera": {"eye": [0, 0, 6], "target": [0, 0, 0], "fov": 50, "width": 80, "height": 48},
      "render": {"spp": 2},
      "objects": [
        {"name": "a", "shape": {"type": "sphere", "radius": 1, "subdivisions": 4}, "transform": {"translate": [-1.2, 0, 0]},
         "material": {"albedo": 0.5}},
        {"name": "b", "shape": {"type": "sphere", "radius": 1, "subdivisions": 4}, "transform": {"translate": [1.2, 0, 0]},
         "material": {"albedo": )" +
           std::to_string(albedo_b) + R"(}}
      ],
      "lights": [{"type": "directional", "direction": [0, 0, 1], "irradiance": 2}, {"type": "ambient", "radiance": 0.1}]
    })";
  };
  testing::TempDir d1, d2;
  const std::vector<nlohmann::json> uses = {with_sigma(0.2), with_sigma(1.0)};
  Rendered bright = render_test_view(d1, scene(0.95), uses),
           dark = render_test_view(d2, scene(0.05), uses);
  for (double sigma : {0.2, 1.0}) {
    auto sa = surface_contrast(bright.scene.objects[0], bright.view->render.vertices.front[0],
                               bright.scene.display, width_of(sigma));
    auto sb = surface_contrast(dark.scene.objects[0], dark.view->render.vertices.front[0],
                               dark.scene.display, width_of(sigma));
    EXPECT_EQ(sa.smooth_lightness, sb.smooth_lightness);
    Composed ea = prepare_method("usm3d", bright.view, with_sigma(sigma))->compose(2.0);
    Composed eb = prepare_method("usm3d", dark.view, with_sigma(sigma))->compose(2.0);
    const GBuffer& g = bright.view->render.gbuffer;
    int pixels = 0;
    for (size_t i = 0; i < g.object.size(); ++i) {
      if (g.object[i] != 0) continue;
      for (int c = 0; c < 3; ++c)
        EXPECT_EQ(ea.display.pixels[3 * i + c], eb.display.pixels[3 * i + c]);
      ++pixels;
    }
    EXPECT_GT(pixels, 200);
  }
}

// The image's mean L* minus the view's.
double mean_lightness_change(const View& view, const Composed& composed) {
  const LabPixels lab = display_to_lab(composed.display, view.encoding, view.bits);
  double sum = 0;
  for (size_t p = 0; p < lab.size(); ++p) sum += lab[p].L - view.lab[p].L;
  return sum / double(lab.size());
}

// The contrast is taken over the whole surface, seen or not, and the image weighs the surface by
// its projected area (docs/enhancement-methods.md, usm3d, "Known behaviour"): a sphere lit from
// above brightens when its lit cap faces the camera and darkens when its unlit one does. The
// same as experiments/drift at a smaller size.
TEST(Usm3d, MeanLightnessDriftFollowsWhatTheCameraSees) {
  auto sphere_seen_from = [](const std::string& eye) {
    return R"({
      "version": 1,
      "camera": {"eye": [)" +
           eye + R"(], "target": [0, 0, 0], "fov": 30, "width": 96, "height": 72},
      "render": {"spp": 4},
      "display": {"background": [0.18, 0.18, 0.18]},
      "objects": [{"shape": {"type": "sphere", "radius": 1, "subdivisions": 5}, "material": {"albedo": 0.5}}],
      "lights": [{"type": "directional", "direction": [0, 1, 0], "irradiance": 1.6}, {"type": "ambient", "radiance": 0.1}]
    })";
  };
  std::map<std::string, double> drift;
  for (const auto& [view, eye] : std::map<std::string, std::string>{
           {"top", "0, 4.6, 2"}, {"side", "0, 0, 5"}, {"bottom", "0, -4.6, 2"}}) {
    testing::TempDir dir;
    const Rendered r = render_test_view(dir, sphere_seen_from(eye), {with_sigma(0.6)});
    const auto usm = prepare_method("usm3d", r.view, with_sigma(0.6));
    drift[view] = mean_lightness_change(*r.view, usm->compose(1.0));
    // In proportion to λ (no clipping here): λ = 2 doubles it within the rounding to code values.
    EXPECT_NEAR(mean_lightness_change(*r.view, usm->compose(2.0)), 2 * drift[view], 0.05) << view;
  }
  EXPECT_GT(drift["top"], 1.0);
  EXPECT_LT(drift["bottom"], -0.2);
  EXPECT_LT(drift["side"], 0.0);  // the terminator's darkened band across the disc
  EXPECT_GT(drift["top"] - drift["side"], 1.0);
}

// A dark decal (a die's pip) on a lit face. As a flattened sphere sunk into the face, its hidden
// part lies in the dark, the pip's smoothed signal is darker than its visible cap, and usm3d
// lightens the whole pip; as a flat disc just above the face it has no hidden part and keeps its
// lightness away from its rim, where it shares pixels with the face's bright border (docs/
// enhancement-methods.md, usm3d, "Known behaviour"; the dice scene's pips).
TEST(Usm3d, ADecalWithoutAHiddenSideKeepsItsLightness) {
  auto scene = [](const std::string& pip) {
    return R"({
      "version": 1,
      "camera": {"eye": [0, 3, 0.6], "target": [0, 0.5, 0], "fov": 20, "width": 128, "height": 96},
      "render": {"spp": 4},
      "objects": [
        {"name": "die", "shape": {"type": "box", "size": [1, 1, 1], "subdivisions": 24}, "transform": {"translate": [0, 0, 0]},
         "material": {"albedo": 0.8}},
        {"name": "pip", )" +
           pip + R"(, "material": {"albedo": 0.04}}
      ],
      "lights": [{"type": "directional", "direction": [0.3, 1, 0.2], "irradiance": 2}, {"type": "ambient", "radiance": 0.1}]
    })";
  };
  const std::string sunk = R"("shape": {"type": "sphere", "radius": 1, "subdivisions": 3},
      "transform": {"matrix": [0.12, 0, 0, 0, 0, 0.04, 0, 0.47, 0, 0, 0.12, 0, 0, 0, 0, 1]})";
  const std::string disc =
      R"("shape": {"type": "disc", "radius": 0.075, "segments": 48}, "transform": {"translate": [0, 0.502, 0]})";
  std::map<std::string, double> change;  // mean L* change over the pip's pixels at λ = 1
  for (const auto& [name, pip] :
       std::map<std::string, std::string>{{"sunk", sunk}, {"disc", disc}}) {
    testing::TempDir dir;
    const Rendered r = render_test_view(dir, scene(pip), {with_sigma(0.1)});
    const Composed out = prepare_method("usm3d", r.view, with_sigma(0.1))->compose(1.0);
    const LabPixels lab = display_to_lab(out.display, r.view->encoding, r.view->bits);
    const GBuffer& g = r.view->render.gbuffer;
    double sum = 0;
    int pixels = 0;
    const int w = r.view->width();
    for (size_t i = 0; i < g.object.size(); ++i)  // the pip's pixels away from its rim
      if (g.object[i] == 1 && g.object[i - 1] == 1 && g.object[i + 1] == 1 &&
          g.object[i - w] == 1 && g.object[i + w] == 1)
        sum += lab[i].L - r.view->lab[i].L, ++pixels;
    ASSERT_GT(pixels, 100) << name;
    change[name] = sum / pixels;
  }
  EXPECT_GT(change["sunk"], 4.0);  // 11.5 L*
  EXPECT_LT(std::abs(change["disc"]), 0.5)
      << change["disc"];  // 0: the disc's signal is its own mean
}

TEST(Usm3d, GainAdaptsWithinBoundsAndNegativeWeightsReverseTheEffect) {
  testing::TempDir d1, d2;
  std::string base = textured_cow();
  Rendered plus = render_test_view(d1, base, {with_sigma(0.1)});
  std::string negative = base;
  negative.replace(negative.find("\"fit\": true"), 11, "\"fit\": true, \"importance\": -1");
  Rendered minus = render_test_view(d2, negative, {with_sigma(0.1)});
  auto sc = surface_contrast(plus.scene.objects[1], plus.view->render.vertices.front[1],
                             plus.scene.display, width_of(0.1));
  for (double g : sc.gain_factor) {
    EXPECT_GE(g, 1.0);
    EXPECT_LE(g, std::sqrt(1.25));  // Var of values in [0,1] is at most 1/4
  }
  auto prepared_plus = prepare_method("usm3d", plus.view, with_sigma(0.1));
  auto prepared_minus = prepare_method("usm3d", minus.view, with_sigma(0.1));
  const std::vector<double>& p = change_of(*prepared_plus).gain;
  const std::vector<double>& m = change_of(*prepared_minus).gain;
  // Inside the cow (its 3×3 neighbourhood all cow, so every sample is): the gain reverses. Edge
  // pixels mix the cow's gain with the floor's, as their samples do.
  const GBuffer& g = plus.view->render.gbuffer;
  auto inside_cow = [&](int x, int y) {
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if (g.object[g.index(std::clamp(x + dx, 0, g.width - 1),
                             std::clamp(y + dy, 0, g.height - 1))] != 1)
          return false;
    return true;
  };
  int cow_pixels = 0;
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x)
      if (inside_cow(x, y)) {
        EXPECT_DOUBLE_EQ(m[g.index(x, y)], -p[g.index(x, y)]);
        ++cow_pixels;
      }
  EXPECT_GT(cow_pixels, 300);
  auto flat = surface_contrast(plus.scene.objects[1], plus.view->render.vertices.front[1],
                               plus.scene.display, SmoothingWidth{0.1, std::nullopt, false});
  for (double g : flat.gain_factor) EXPECT_EQ(g, 1.0);
}

TEST(Usm3d, RingSamplesLieInsideTheTriangleAndSpreadOverIt) {
  for (int k : {1, 3, 8}) {
    glm::dvec3 mean(0.0);
    for (int j = 0; j < k; ++j) {
      glm::dvec3 b = triangle_sample_barycentrics(j, k);
      EXPECT_NEAR(b.x + b.y + b.z, 1.0, 1e-12);
      EXPECT_GE(std::min({b.x, b.y, b.z}), 0.0);
      mean += b / double(k);
    }
    if (k >= 3) {
      EXPECT_NEAR(mean.x, 1.0 / 3.0, 0.15);
    }
  }
}

TEST(Usm3d, ParsesItsParametersAndRejectsTheRest) {
  const EnhancementMethod& m = method_named("usm3d", "test");
  auto parse = [&](const nlohmann::json& j) {
    return m.parse(ParameterBag::from_json(j, "exp.json", "methods[0]"));
  };
  EXPECT_THROW(parse(nlohmann::json::object()), InputError);
  EXPECT_THROW(parse({{"sigma", 0.1}, {"iterations", 3}}), InputError);
  EXPECT_THROW(parse(with_sigma(-1)), InputError);
  EXPECT_THROW(m.parse(ParameterBag::from_arguments({"--sigma", "nan"})), InputError);
  EXPECT_NO_THROW(parse(with_sigma(0.1)));
  // A key usm3d does not use names the method and the key, from a file and from the command line.
  std::string message = testing::input_error_of([&] { parse({{"sigma", 0.1}, {"kernel", 5}}); });
  EXPECT_NE(message.find("exp.json: methods[0].kernel"), std::string::npos) << message;
  EXPECT_NE(message.find("usm3d has no parameter 'kernel'"), std::string::npos) << message;
  message = testing::input_error_of([&] {
    m.parse(ParameterBag::from_arguments({"--kernel", "5%", "--operator", "add"}));
  });
  EXPECT_NE(message.find("--kernel: usm3d has no parameter 'kernel'"), std::string::npos)
      << message;
  // Of several, the first one typed.
  message = testing::input_error_of([&] {
    m.parse(
        ParameterBag::from_arguments({"--sigma", "0.1", "--operator", "add", "--kernel", "5%"}));
  });
  EXPECT_NE(message.find("--operator: usm3d has no parameter 'operator'"), std::string::npos)
      << message;
}

}  // namespace
}  // namespace countershade
