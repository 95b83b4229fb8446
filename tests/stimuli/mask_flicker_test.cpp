// The mask of a method (the low-pass signal M of U = S + λ(S − M)) and its flicker: each unsharp
// method's mask is what its layer is taken against; a mask attached to the surface survives the
// reprojection through a set's mask files and one fixed to the screen does not; a sequence set
// records the mask flicker the `flicker` command measures; the region near an object.

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>

#include "enhance/lightness.h"
#include "enhance/registry.h"
#include "enhance/view_plan.h"
#include "measures/flicker.h"
#include "render/scene_animation.h"
#include "render/scene_loader.h"
#include "stimuli/mask_file.h"
#include "stimuli/set_test_util.h"
#include "stimuli/surface_values.h"
#include "test_util.h"

namespace countershade {
namespace {

namespace fs = std::filesystem;

// The view of the orbiting box's first frame, rendered for `method` at 16 bits.
struct Prepared {
  std::shared_ptr<const View> view;
  std::unique_ptr<PreparedEnhancement> prepared;
};
Prepared prepare(const fs::path& scene_file, const std::string& method,
                 const nlohmann::json& parameters) {
  auto scene = std::make_shared<Scene>(load_scene(scene_file));
  scene->animation.reset();
  ViewOptions options;
  options.bits = 16;
  Prepared out;
  out.view = render_view(scene, plan_for(method, parameters, 1.0), options);
  const EnhancementMethod& m = method_named(method, "test");
  out.prepared = m.prepare(make_use_context(out.view, 0, 0),
                           *m.parse(ParameterBag::from_json(parameters, "test", method)));
  return out;
}

// Over the pixels with all 8 neighbours on one object and no channel clipped: the largest
// |(enhanced − plain L*) − λ·(S − M)| for λ = 1, where S is the plain L*.
double largest_departure(const Prepared& p, const std::vector<float>& mask) {
  const Image enhanced = p.prepared->compose(1.0).display;
  const std::vector<float> layer = enhancement_layer(*p.view, enhanced);
  const std::vector<float> plain = view_lightness(*p.view);
  const int w = p.view->width(), h = p.view->height();
  double largest = 0;
  for (int y = 1; y + 1 < h; ++y)
    for (int x = 1; x + 1 < w; ++x) {
      const size_t i = size_t(y) * w + x;
      bool inside = p.view->object_at(i) >= 0;
      for (int c = 0; c < 3; ++c)
        inside = inside && enhanced.pixels[3 * i + c] > 0 && enhanced.pixels[3 * i + c] < 1;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          inside = inside && p.view->object_at(i + dy * w + dx) == p.view->object_at(i);
      if (inside)
        largest = std::max(largest, std::abs(double(layer[i]) - (double(plain[i]) - mask[i])));
    }
  return largest;
}

TEST(MethodMask, TheLayerOfEachUnsharpMethodIsTakenAgainstItsMask) {
  testing::TempDir dir;
  const fs::path scene = testing::write_file(dir / "orbit.json", testing::kOrbitingBoxScene);
  for (const auto& [method, parameters] : std::vector<std::pair<std::string, nlohmann::json>>{
           {"usm2d", {{"sigma_px", 3}}},
           {"texture-filter", {{"mode", "post"}, {"filter", "unsharp"}, {"sigma", 3}}},
           {"usm3d", {{"sigma", 0.1}, {"adapt", false}}}}) {
    SCOPED_TRACE(method);
    const Prepared p = prepare(scene, method, parameters);
    const std::vector<float> mask = p.prepared->mask();
    ASSERT_EQ(mask.size(), p.view->depth.size());
    EXPECT_LT(largest_departure(p, mask), 0.05);  // 16-bit codes: far below one 8-bit level
    std::vector<float> shifted = mask;            // a wrong mask is seen: the check can fail
    for (float& m : shifted) m += 0.5f;
    EXPECT_GT(largest_departure(p, shifted), 0.4);
  }
}

TEST(MethodMask, DepthUsmGivesItsImportanceAndOtherMethodsNone) {
  testing::TempDir dir;
  const fs::path scene = testing::write_file(dir / "orbit.json", testing::kOrbitingBoxScene);
  const Prepared depth = prepare(scene, "depth-usm", {{"sigma_px", 4}});
  const std::vector<float> mask = depth.prepared->mask();
  const auto importance = depth.prepared->auxiliary();
  ASSERT_EQ(importance.size(), 3u);
  ASSERT_EQ(importance[2].first, "spatial_importance");
  ASSERT_EQ(mask.size(), importance[2].second.pixels.size());
  for (size_t i = 0; i < mask.size(); i += 97)
    EXPECT_FLOAT_EQ(mask[i], 100.0f * importance[2].second.pixels[i]);
  EXPECT_TRUE(prepare(scene, "cornsweet", {{"sigma_px", 3}}).prepared->mask().empty());
}

// A value per pixel from the surface point it sees, in the box's own frame for the box, which
// the orbiting box scene moves by 0.4 along x per second.
std::vector<float> attached(const View& v, double time,
                            const std::function<double(const glm::dvec3&)>& f) {
  return testing::surface_values(v, [&](const glm::dvec3& p, int object) {
    return f(object == 1 ? p - glm::dvec3(0.4 * time, 0, 0) : p);
  });
}

TEST(MaskFlicker, AMaskOnTheSurfaceHoldsStillThroughItsFilesAndOneOnTheScreenDoesNot) {
  testing::TempDir dir;
  const fs::path file = testing::write_file(dir / "orbit.json", testing::kOrbitingBoxScene);
  const Scene base = load_scene(file);
  const auto a =
      geometry_view(std::make_shared<const Scene>(scene_at(base, base.animation->time_of(0))), 1);
  const auto b =
      geometry_view(std::make_shared<const Scene>(scene_at(base, base.animation->time_of(1))), 1);
  const auto smooth = [](const glm::dvec3& p) {
    return 50 + 20 * std::sin(3 * p.x) * std::cos(2 * p.z) + 10 * p.y;
  };
  const auto on_screen = [](const View& v) {
    std::vector<float> m(v.depth.size());
    for (size_t i = 0; i < m.size(); ++i)
      m[i] = float(50 + 20 * std::sin(0.4 * double(i % size_t(v.width()))));
    return m;
  };
  // Through the set's files: 16-bit codes over [−100, 200] L*.
  const auto through_file = [&](const View& v, const std::vector<float>& m, const char* name) {
    write_mask(dir.path(), name, m, v.width(), v.height());
    const std::vector<float> back = read_mask(dir / name);
    for (size_t i = 0; i < m.size(); ++i) EXPECT_NEAR(back[i], m[i], 0.0024);
    return back;
  };
  const CarryPoint carry = carry_between_frames(base, 0, 1);
  const Reprojection surface = reprojection_rms(
      *a, through_file(*a, attached(*a, 0.0, smooth), "a.png"), *b,
      through_file(*b, attached(*b, base.animation->time_of(1), smooth), "b.png"), carry);
  const Reprojection screen = reprojection_rms(*a, on_screen(*a), *b, on_screen(*b), carry);
  EXPECT_GT(surface.pixels, 500u);
  EXPECT_LT(surface.rms, 0.05);
  EXPECT_GT(screen.rms, 0.5);
}

// The `flicker` command's mask flicker, in process: one method at λ = 1 over every frame.
std::map<int, double> command_mask_flicker(const fs::path& scene_file, const std::string& method,
                                           const nlohmann::json& parameters) {
  const EnhancementMethod& m = method_named(method, "test");
  FlickerRender render;
  render.method = &m;
  render.parameters = m.parse(ParameterBag::from_json(parameters, "test", method));
  render.component = FlickerComponent::mask;
  Scene base = load_scene(scene_file);
  apply_request(base, m.request(*render.parameters));
  std::map<int, double> out;
  measure_rendered_flicker(
      base, 0, base.animation->frame_count() - 1, render, {},
      [&](int frame, const FlickerFrame&, const FlickerFrame&, const PlainChange&,
          const PairFlicker& pair) { out[frame] = pair.layer.rms; });
  return out;
}

TEST(MaskFlicker, ASequenceSetRecordsTheMaskFlickerOfTheFlickerCommand) {
  testing::TempDir dir;
  testing::write_file(dir / "orbit.json", testing::kOrbitingBoxScene);
  const fs::path experiment = testing::write_file(dir / "experiment.json", R"({
    "version": 1, "name": "masks", "seed": 7, "lambda": {"min": 0, "max": 1, "step": 1},
    "scenes": [{"name": "orbit", "file": "orbit.json", "frames": "all"}],
    "methods": [{"method": "usm2d", "sigma_percent": [3]}, {"method": "none"}]})");
  const Experiment e = load_experiment(experiment);
  generate_stimulus_set(e, dir / "set", testing::with_jobs(2));
  testing::draw_figures(e, dir / "set", false);
  const std::map<int, double> command =
      command_mask_flicker(dir / "orbit.json", "usm2d", {{"sigma_percent", 3}});
  const OrderedJson manifest = testing::manifest_json(dir / "set");
  int compared = 0;
  for (const auto& s : manifest["stimuli"]) {
    if (s["method"] != "usm2d") {
      EXPECT_FALSE(s.contains("mask")) << s["file"];  // the plain render and `none` have no mask
      continue;
    }
    ASSERT_TRUE(s.contains("mask")) << s["file"];
    EXPECT_EQ(s["mask"]["file"],
              "orbit/usm2d/sigma-3/mask/frame-000" + std::to_string(int(s["frame"])) + ".png");
    if (s["frame"] == 0) continue;
    EXPECT_NEAR(s["mask_flicker"].get<double>(), command.at(s["frame"]), 0.003) << s["file"];
    ++compared;
  }
  EXPECT_EQ(compared, 6);          // 3 frame pairs × 2 λ
  EXPECT_GT(command.at(1), 0.05);  // the masks do change: the comparison can tell
  EXPECT_TRUE(fs::exists(dir / "set" / "flicker-mask-orbit.svg"));
  EXPECT_TRUE(verify_stimulus_set(dir / "set" / "manifest.json").empty());
  fs::remove(dir / "set" / "orbit/usm2d/sigma-3/mask/frame-0002.png");
  EXPECT_FALSE(verify_stimulus_set(dir / "set" / "manifest.json").empty());  // a lost mask is seen
}

TEST(FlickerRegion, PixelsOfOneObjectNearAnother) {
  testing::TempDir dir;
  const fs::path file = testing::write_file(dir / "orbit.json", testing::kOrbitingBoxScene);
  const auto view = geometry_view(std::make_shared<const Scene>(load_scene(file)), 1);
  FlickerOptions o;
  o.on = 0;    // the ground
  o.near = 1;  // the box
  o.within_px = 3;
  const std::vector<char> region = region_pixels(*view, o);
  const int w = view->width(), h = view->height();
  size_t in = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      bool near = false;  // brute force: a box pixel within 3 px
      for (int v = 0; v < h; ++v)
        for (int u = 0; u < w; ++u)
          near = near || (view->object_at(size_t(v) * w + u) == 1 &&
                          (u - x) * (u - x) + (v - y) * (v - y) <= 9);
      const size_t i = size_t(y) * w + x;
      EXPECT_EQ(bool(region[i]), near && view->object_at(i) == 0) << x << "," << y;
      in += region[i];
    }
  EXPECT_GT(in, 50u);
}

}  // namespace
}  // namespace countershade
