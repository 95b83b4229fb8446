// Perspective coherence: a layer attached to the surface survives the dolly's reprojection, a layer
// fixed to the screen does not; and a set that asks for the metric records it and plots it.

#include "measures/perspective_coherence.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <map>
#include <numbers>

#include "enhance/view_plan.h"
#include "render/scene_loader.h"
#include "stimuli/experiment.h"
#include "stimuli/set_test_util.h"
#include "stimuli/stimulus_set.h"
#include "stimuli/surface_values.h"
#include "test_util.h"

namespace countershade {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = std::numbers::pi;

const char* kGround = R"({"version": 1,
  "camera": {"eye": [0, 1.5, 4], "target": [0, 0.2, -6], "fov": 50, "width": 96, "height": 72},
  "render": {"spp": 1},
  "objects": [{"name": "ground", "shape": {"type": "plane", "size": 40, "subdivisions": 4},
               "material": {"texture": {"size": 64, "squares": 8}, "texture_repeat": 4}}],
  "lights": [{"type": "directional", "direction": [0.3, 1, 0.4], "irradiance": 2, "shadows": false}]})";

std::shared_ptr<const View> ground_view(const fs::path& file, double dolly) {
  auto scene = std::make_shared<Scene>(load_scene(file));
  scene->camera = dollied(scene->camera, dolly);
  return render_view(scene);
}

// A value per pixel from the world point the pixel sees.
std::vector<float> attached(const View& v, const std::function<double(const glm::dvec3&)>& f) {
  return testing::surface_values(v, [&](const glm::dvec3& p, int) { return f(p); });
}

std::vector<float> screen_fixed(const View& v) {
  std::vector<float> out(v.depth.size());
  for (size_t i = 0; i < out.size(); ++i)
    out[i] = float(5 * std::sin(2 * kPi * double(i % size_t(v.width())) / 12));
  return out;
}

TEST(PerspectiveCoherence, ADollyMovesTheEyeTowardsTheTarget) {
  Camera c;
  c.eye = {0, 0, 10};
  c.target = {0, 0, 0};
  EXPECT_EQ(dollied(c, 0.02).eye, glm::dvec3(0, 0, 9.8));
  EXPECT_EQ(dollied(c, 0.02).target, c.target);
}

TEST(PerspectiveCoherence, ALayerOnTheSurfaceIsCoherentAndOneOnTheScreenIsNot) {
  testing::TempDir dir;
  const fs::path file = testing::write_file(dir / "ground.json", kGround);
  const auto first = ground_view(file, 0), moved = ground_view(file, 0.02);
  auto wave = [](const glm::dvec3& p) {
    return 5 * std::sin(2 * kPi * p.x / 3) * std::cos(2 * kPi * p.z / 4);
  };
  const Reprojection on_surface =
      reprojection_rms(*first, attached(*first, wave), *moved, attached(*moved, wave));
  const Reprojection on_screen =
      reprojection_rms(*first, screen_fixed(*first), *moved, screen_fixed(*moved));
  // The ground fills the lower half of the frame; the rows nearest the horizon (depth changing
  // fast) and the borders drop out.
  EXPECT_GT(on_surface.pixels, size_t(96 * 72 / 4));
  EXPECT_EQ(on_screen.pixels, on_surface.pixels);
  EXPECT_LT(on_surface.rms, 0.05);
  EXPECT_GT(on_screen.rms, 0.5) << "on the surface " << on_surface.rms;
  const Reprojection same =
      reprojection_rms(*first, screen_fixed(*first), *first, screen_fixed(*first));
  EXPECT_LT(same.rms, 1e-5);  // no motion: every pixel lands on itself
}

// A pixel next to another object mixes both in its value (its area covers both), so it is not a
// point of one surface: it does not count, in the first frame as in the moved one. Here an
// "occluder" (object 1, a strip of columns) moves right between two views of a still camera; the
// first frame's pixels beside it hold a mixed value, which once the occluder has left would read
// as a change of the surface behind it.
TEST(PerspectiveCoherence, PixelsBesideAnotherObjectDoNotCount) {
  testing::TempDir dir;
  const auto view = ground_view(testing::write_file(dir / "ground.json", kGround), 0);
  View first = *view, moved = *view;
  ASSERT_FALSE(first.render.gbuffer.object.empty());
  const int w = first.width();
  std::vector<float> first_values(first.depth.size(), 0.0f), moved_values(first.depth.size(), 0.0f);
  for (size_t i = 0; i < first.depth.size(); ++i) {
    const int x = int(i % size_t(w));
    if (x >= 40 && x < 56) first.render.gbuffer.object[i] = 1;
    if (x >= 48 && x < 64) moved.render.gbuffer.object[i] = 1;
    if (x == 39 || x == 56) first_values[i] = 3.0f;  // half ground, half occluder
  }
  const Reprojection r = reprojection_rms(first, first_values, moved, moved_values);
  EXPECT_GT(r.pixels, size_t(96 * 72 / 4));
  EXPECT_EQ(r.rms, 0.0);
}

TEST(PerspectiveCoherence, ASetRecordsEveryStimulusAndPlotsIt) {
  testing::TempDir dir;
  testing::write_file(dir / "ground.json", kGround);
  ::setenv("COUNTERSHADE_CACHE", (dir / "cache").c_str(), 1);
  const fs::path file = testing::write_file(dir / "experiment.json", R"({
    "version": 1, "name": "coherent", "seed": 3, "coherence": {"dolly": 0.02},
    "lambda": {"min": 0.5, "max": 1, "step": 0.5},
    "scenes": [{"name": "ground", "file": "ground.json"}],
    "methods": [{"method": "texture-filter", "mode": "texture", "sigma": [1]},
                {"method": "texture-filter", "mode": "post", "sigma": [1]}]})");
  const Experiment e = load_experiment(file);
  generate_stimulus_set(e, dir / "set", {});
  testing::draw_figures(e, dir / "set", false);
  EXPECT_TRUE(verify_stimulus_set(dir / "set/manifest.json").empty());
  const std::string csv = testing::read_file(dir / "set/coherence.csv");
  EXPECT_EQ(testing::count_lines(csv), 1 + 1 + 2 * 2);  // header, plain, two methods at two λ
  EXPECT_NE(csv.find("ground,plain,,"), std::string::npos) << csv;
  EXPECT_TRUE(fs::exists(dir / "set/coherence-ground.svg"));
  const std::string manifest = testing::read_file(dir / "set/manifest.json");
  EXPECT_NE(manifest.find("\"coherence_pixels\""), std::string::npos);
  // Every enhanced stimulus also over the pixels where the plain render is stable, a subset; there
  // texture mode, on the surface, changes less than post mode, on the screen.
  std::map<std::string, double> stable;                       // "mode λ" → coherence_stable
  const OrderedJson m = testing::manifest_json(dir / "set");  // alive while iterating
  for (const auto& s : m["stimuli"]) {
    if (s["method"] == "none") continue;
    ASSERT_TRUE(s.contains("coherence_stable")) << s["file"];
    const size_t all = s["coherence_pixels"], within = s["coherence_stable_pixels"];
    EXPECT_GT(within, all / 10);
    EXPECT_LE(within, all);
    stable[s["parameters"]["mode"].get<std::string>() + " " +
           std::to_string(s["lambda"].get<double>())] = s["coherence_stable"];
  }
  ASSERT_EQ(stable.size(), 4u);
  EXPECT_LT(stable.at("texture 1.000000"), stable.at("post 1.000000"));
  EXPECT_NE(csv.find("coherence_stable_lstar"), std::string::npos);
}

TEST(PerspectiveCoherence, ADollyOutOfRangeIsAnError) {
  testing::TempDir dir;
  testing::write_file(dir / "ground.json", kGround);
  const fs::path file = testing::write_file(dir / "experiment.json", R"({
    "version": 1, "coherence": {"dolly": 0.9}, "scenes": [{"name": "g", "file": "ground.json"}],
    "methods": [{"method": "none"}]})");
  EXPECT_NE(testing::input_error_of([&] { load_experiment(file); }).find("coherence.dolly"),
            std::string::npos);
}

}  // namespace
}  // namespace countershade
