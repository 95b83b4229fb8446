// Coverage-correct contrast: surfaces of uniform radiance carry no contrast, so an enhancement
// must leave them unchanged, including anti-aliased silhouette pixels, occlusion boundaries and
// pixels shared by two objects (an outline there would be a confound observers could judge).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/image.h"
#include "enhance/lightness.h"
#include "enhance/registry.h"
#include "enhance/view_plan.h"
#include "render/ray_tracer.h"
#include "render/scene_loader.h"
#include "test_util.h"

namespace countershade {
namespace {

// Uniform radiance: one ambient light without occlusion, so every hit of an object has
// radiance albedo × 0.7 whatever its position or normal.
std::string uniform_scene(const std::string& objects,
                          const std::string& lights = R"({"type": "ambient", "radiance": 0.7})") {
  return R"({
    "version": 1,
    "camera": {"eye": [0.4, 1.6, 4.2], "target": [0, 0.1, 0], "fov": 34, "width": 120, "height": 90},
    "display": {"background": 0.05},
    "objects": [)" +
         objects + R"(],
    "lights": [)" +
         lights + R"(]
  })";
}

// A sphere, a box and a cylinder apart, on a dark background.
const std::string kPrimitives = R"(
  {"shape": {"type": "sphere", "radius": 0.5, "subdivisions": 4}, "transform": {"translate": [-1.1, 0, 0]},
   "material": {"albedo": 0.8}},
  {"shape": {"type": "box", "size": [0.8, 0.8, 0.8], "subdivisions": 8}, "transform": {"rotate": [0, 30, 0]},
   "material": {"albedo": 0.6}},
  {"shape": {"type": "cylinder", "radius": 0.35, "height": 1.0}, "transform": {"translate": [1.1, 0, 0]},
   "material": {"albedo": [0.9, 0.5, 0.3]}})";

// A light sphere sunk into a dark box: the two share the pixels along their intersection curve.
const std::string kOverlapping = R"(
  {"shape": {"type": "box", "size": [1.6, 0.8, 0.8], "subdivisions": 8}, "material": {"albedo": 0.15}},
  {"shape": {"type": "sphere", "radius": 0.5, "subdivisions": 4}, "transform": {"translate": [0.2, 0.3, 0.2]},
   "material": {"albedo": 0.9}})";

// A dark cylinder well in front of a light box, hiding part of it: an occlusion boundary with
// depth.
const std::string kOccluded = R"(
  {"shape": {"type": "box", "size": [1.8, 1.0, 0.6], "subdivisions": 8}, "transform": {"translate": [0, 0, -0.8]},
   "material": {"albedo": 0.85}},
  {"shape": {"type": "cylinder", "radius": 0.25, "height": 1.4, "segments": 48}, "transform": {"translate": [0.3, 0, 0.9]},
   "material": {"albedo": 0.1}})";

struct LevelDifference {
  int max_levels = 0;
  size_t changed_pixels = 0;  // pixels where any channel differs
};

LevelDifference compare_levels(const Image& a, const Image& b) {
  LevelDifference d;
  for (size_t p = 0; p < a.pixels.size() / 3; ++p) {
    int worst = 0;
    for (int c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(int(quantize(a.pixels[3 * p + c], 8)) -
                                       int(quantize(b.pixels[3 * p + c], 8))));
    d.max_levels = std::max(d.max_levels, worst);
    d.changed_pixels += worst > 0;
  }
  return d;
}

// Renders `scene_json` once for usm3d at each width and returns the largest change over every λ
// of a grid up to 3 (both signs).
int usm3d_largest_change(const std::string& scene_json, const std::string& what) {
  testing::TempDir dir;
  auto scene = std::make_shared<Scene>(load_scene(testing::write_file(dir / "s.json", scene_json)));
  const std::vector<double> sigmas = {0.05, 0.3};
  ViewPlan plan;
  plan.max_abs_lambda = 3;
  for (double sigma : sigmas) plan.add("usm3d", {{"sigma", sigma}});
  auto view = render_view(scene, plan, ViewOptions{});
  size_t background = 0, objects_seen = 0;
  for (int id : view->render.gbuffer.object) (id < 0 ? background : objects_seen) += 1;
  EXPECT_GT(background, 1000u) << what;
  EXPECT_GT(objects_seen, 1000u) << what;
  int largest = 0;
  for (double sigma : sigmas) {
    auto usm = prepare_method("usm3d", view, {{"sigma", sigma}});
    for (double lambda = -3; lambda <= 3; lambda += 0.5) {
      LevelDifference d = compare_levels(usm->compose(lambda).display, view->display);
      largest = std::max(largest, d.max_levels);
      EXPECT_EQ(d.changed_pixels, 0u) << what << " σ=" << sigma << " λ=" << lambda << " ("
                                      << d.changed_pixels << " pixels changed)";
    }
  }
  return largest;
}

void expect_usm3d_leaves_unchanged(const std::string& objects, const std::string& what) {
  EXPECT_LE(usm3d_largest_change(uniform_scene(objects), what), 1);
}

TEST(Silhouettes, UniformPrimitivesOnAContrastingBackgroundAreUnchanged) {
  expect_usm3d_leaves_unchanged(kPrimitives, "primitives");
}

// The control: the same objects under a directional light have shading contrast, and change.
TEST(Silhouettes, ShadedPrimitivesDoChange) {
  const std::string sun = R"({"type": "directional", "direction": [0.6, 1, 0.4], "irradiance": 2})";
  testing::TempDir dir;
  auto scene = std::make_shared<Scene>(
      load_scene(testing::write_file(dir / "s.json", uniform_scene(kPrimitives, sun))));
  auto view = render_view(scene, plan_for("usm3d", {{"sigma", 0.3}}, 3.0), ViewOptions{});
  LevelDifference d = compare_levels(
      prepare_method("usm3d", view, {{"sigma", 0.3}})->compose(3.0).display, view->display);
  EXPECT_GT(d.max_levels, 10);
  EXPECT_GT(d.changed_pixels, 300u);
}

TEST(Silhouettes, TwoOverlappingUniformObjectsAreUnchanged) {
  expect_usm3d_leaves_unchanged(kOverlapping, "overlapping");
}

TEST(Silhouettes, APartlyOccludedUniformObjectIsUnchanged) {
  expect_usm3d_leaves_unchanged(kOccluded, "occluded");
}

// Consistent sides: the camera looks at a plane (an open mesh) from below, where a directional
// light shines on it evenly. The vertex signal must be shaded for that side too; shaded for the
// top, which no light reaches, it would differ from the pixels everywhere and usm3d would darken
// the whole plane.
TEST(Silhouettes, APlaneSeenFromBehindIsUnchangedUnderEvenLight) {
  const std::string scene = R"({
    "version": 1,
    "camera": {"eye": [0.3, -3, 1.5], "target": [0, 0, 0], "fov": 40, "width": 100, "height": 80},
    "display": {"background": 0.6},
    "objects": [{"shape": {"type": "plane", "size": 2, "subdivisions": 20}, "material": {"albedo": 0.4}}],
    "lights": [{"type": "directional", "direction": [0.2, -1, 0.1], "irradiance": 1.2}]
  })";
  EXPECT_LE(usm3d_largest_change(scene, "plane from below"), 1);
}

// The Cornsweet surface mode adds its profile to the surface, so the object does change; at the
// silhouette a pixel changes by no more than its covered share of the change inside the object:
// never more than the largest change of a fully covered neighbour, so no outline appears.
TEST(Silhouettes, CornsweetSurfaceProfileDrawsNoOutline) {
  testing::TempDir dir;
  auto scene = std::make_shared<Scene>(load_scene(testing::write_file(
      dir / "s.json",
      uniform_scene(
          R"({"shape": {"type": "box", "size": [1.2, 1.2, 1.2], "subdivisions": 12}, "transform": {"rotate": [0, 25, 0]},
          "material": {"albedo": 0.5}})"))));
  const nlohmann::json o = {{"mode", "surface"},
                            {"sigma", 0.15},
                            {"edge_point", {0, 0.6, 0}},
                            {"edge_direction", {1, 0, 0}},
                            {"bright_normal", {0, 1, 0}}};
  auto view = render_view(scene, plan_for("cornsweet", o, 3.0), ViewOptions{});
  const GBuffer& g = view->render.gbuffer;
  const int w = view->display.width, h = view->display.height;
  auto changed = [&](const Image& out, int x, int y) {
    return std::abs(display_pixel_to_lab(&out.pixels[3 * (size_t(y) * w + x)], view->encoding).L -
                    view->lab[size_t(y) * w + x].L);
  };
  for (double lambda : {1.0, 3.0}) {
    Image out = prepare_method("cornsweet", view, o)->compose(lambda).display;
    int silhouette_pixels = 0;
    for (int y = 1; y + 1 < h; ++y)
      for (int x = 1; x + 1 < w; ++x) {
        if (g.object[size_t(y) * w + x] >= 0)
          continue;  // background at the centre: an edge pixel at most
        double inside = 0;
        bool next_to_object = false;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx)
            if (g.object[size_t(y + dy) * w + x + dx] >= 0) {
              next_to_object = true;
              inside = std::max(inside, changed(out, x + dx, y + dy));
            }
        if (!next_to_object) continue;
        ++silhouette_pixels;
        EXPECT_LE(changed(out, x, y), inside + 0.5) << "λ=" << lambda << " at " << x << "," << y;
      }
    EXPECT_GT(silhouette_pixels, 100);
  }
}

}  // namespace
}  // namespace countershade
