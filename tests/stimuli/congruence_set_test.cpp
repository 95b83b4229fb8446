// Sets that score congruence: scenes swept over view-relative light directions, the score and map
// of every stimulus in the manifest (checked like the stimuli), and the figures.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <glm/geometric.hpp>

#include "core/error.h"
#include "enhance/view_plan.h"
#include "measures/congruence.h"
#include "render/camera.h"
#include "stimuli/experiment.h"
#include "stimuli/set_test_util.h"
#include "stimuli/stimulus_set.h"
#include "test_util.h"

namespace countershade {
namespace {

namespace fs = std::filesystem;

fs::path write_ball_experiment(const testing::TempDir& dir, const std::string& directions) {
  testing::write_file(dir / "ball.json", R"({
    "version": 1,
    "camera": {"eye": [0, 1, 5], "target": [0, 0, 0], "fov": 30, "width": 48, "height": 36},
    "render": {"spp": 2},
    "objects": [{"shape": {"type": "sphere", "radius": 1, "subdivisions": 3}, "material": {"albedo": 0.6}}],
    "lights": [{"type": "directional", "direction": [0, 0, 1], "irradiance": 2, "shadows": false}]
  })");
  return testing::write_file(dir / "experiment.json", R"({
    "version": 1, "name": "sweep", "seed": 3, "congruence": true,
    "lambda": {"min": 1, "max": 1, "step": 1},
    "scenes": [{"name": "ball", "file": "ball.json", "light_directions": )" +
                                                          directions + R"(}],
    "methods": [{"method": "none"}, {"method": "radiance-scaling", "tau": 4}]
  })");
}

TEST(CongruenceSet, LightDirectionsAreRelativeToTheView) {
  Camera camera;
  camera.eye = {0, 1, 5}, camera.target = {0, 0, 0};
  const CameraRays rays(camera);
  EXPECT_LT(glm::length(view_light_direction(camera, {0, 0}) + rays.forward()),
            1e-12);  // towards the viewer
  EXPECT_LT(glm::length(view_light_direction(camera, {0, 90}) - rays.right()), 1e-12);
  EXPECT_NEAR(glm::dot(view_light_direction(camera, {60, 200}), rays.up()), std::sqrt(3.0) / 2,
              1e-12);
  // Around the image plane: azimuth 0 from the right, 90 from above, the elevation towards the
  // viewer.
  EXPECT_LT(glm::length(view_light_direction(camera, {0, 0, true}) - rays.right()), 1e-12);
  EXPECT_LT(glm::length(view_light_direction(camera, {0, 90, true}) - rays.up()), 1e-12);
  for (double azimuth : {0.0, 102.9, 205.7, 308.6})
    EXPECT_NEAR(glm::dot(view_light_direction(camera, {15, azimuth, true}), -rays.forward()),
                std::sin(15.0 * M_PI / 180.0), 1e-12);
}

TEST(CongruenceSet, EveryStimulusIsScoredAndItsMapCheckedLikeTheStimuli) {
  testing::TempDir dir;
  const Experiment e =
      load_experiment(write_ball_experiment(dir, R"({"elevations": [0, 60], "azimuths": 4})"));
  ASSERT_EQ(e.scenes.size(), 8u);
  EXPECT_EQ(e.scenes[1].name, "ball-e0-a90");
  EXPECT_EQ(e.scenes[7].name, "ball-e60-a270");
  GenerateOptions options;
  options.jobs = 2;
  generate_stimulus_set(e, dir / "set", options);
  testing::draw_figures(e, dir / "set");
  EXPECT_TRUE(verify_stimulus_set(dir / "set/manifest.json").empty());

  // The recorded score is the score of the written pixels against the scene's depth.
  const Manifest manifest = read_manifest(dir / "set/manifest.json");
  ASSERT_EQ(manifest.stimuli.size(), 8u * 3u);  // reference, none, radiance-scaling per scene
  const auto view = render_view(std::make_shared<Scene>(load_experiment_scene(e, e.scenes[0])));
  const ManifestEntry& reference = *std::find_if(
      manifest.stimuli.begin(), manifest.stimuli.end(),
      [&](const ManifestEntry& s) { return s.is_reference() && s.scene == e.scenes[0].name; });
  int bits = 0;
  const Image written = read_image(dir / "set" / reference.file, &bits);
  const double score = display_congruence(written, view->encoding, bits, view->depth).score;
  EXPECT_NEAR(reference.extra["congruence"].get<double>(), score, 1e-4);
  EXPECT_GT(score, 0.3);  // a lit ball's shading follows its shape
  for (const auto& s : manifest.stimuli) EXPECT_TRUE(s.extra.contains("congruence_map")) << s.file;
  // The method `none` is a condition of its own, not a second reference.
  EXPECT_EQ(std::count_if(manifest.stimuli.begin(), manifest.stimuli.end(),
                          [](const ManifestEntry& s) { return s.is_reference(); }),
            8);

  // The figures: one table row per scene and condition, the plot and a sheet per condition.
  std::ifstream csv(dir / "set/congruence.csv");
  int lines = 0;
  for (std::string line; std::getline(csv, line);) ++lines;
  EXPECT_EQ(lines, 1 + 8 * 3);
  EXPECT_TRUE(fs::is_regular_file(dir / "set/congruence.svg"));
  EXPECT_TRUE(fs::is_regular_file(dir / "set/contact-sheets/congruence-radiance-scaling.png"));
  EXPECT_FALSE(fs::exists(
      dir / "set/contact-sheets/ball-e0-a0-radiance-scaling.png"));  // one image: no sheet

  // A changed map is reported.
  const std::string map = manifest.stimuli[2].extra["congruence_map"]["file"].get<std::string>();
  std::ofstream(dir / "set" / map, std::ios::app) << "x";
  const auto problems = verify_stimulus_set(dir / "set/manifest.json");
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find(map + ": sha256 differs"), std::string::npos);
}

// Two scene entries that each sweep the light: besides the plot over all scenes, one plot per
// entry whose x axis numbers its own directions from 1.
TEST(CongruenceSet, EachSweptSceneGetsAFigureOfItsOwn) {
  testing::TempDir dir;
  write_ball_experiment(dir, "{}");
  testing::write_file(dir / "two.json", R"({
    "version": 1, "name": "two", "seed": 3, "congruence": true,
    "lambda": {"min": 1, "max": 1, "step": 1},
    "scenes": [{"name": "near", "file": "ball.json", "light_directions": {"elevations": [30], "azimuths": 3}},
               {"name": "far", "file": "ball.json", "light_directions": {"elevations": [30, 60], "azimuths": 2}}],
    "methods": [{"method": "none"}]
  })");
  const Experiment e = load_experiment(dir / "two.json");
  ASSERT_EQ(e.scenes.size(), 7u);
  EXPECT_EQ(e.scenes[4].swept_from, "far");
  GenerateOptions options;
  options.jobs = 2;
  generate_stimulus_set(e, dir / "set", options);
  testing::draw_figures(e, dir / "set", false);
  auto points_in = [](const fs::path& svg) {  // the vertices of every line's polyline
    std::ifstream in(svg);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    size_t count = 0;
    for (size_t at = text.find("points=\""); at != std::string::npos;
         at = text.find("points=\"", at + 1)) {
      const size_t begin = at + 8, end = text.find('"', begin);
      count += size_t(std::count(text.begin() + long(begin), text.begin() + long(end), ','));
    }
    return count;
  };
  const size_t all = points_in(dir / "set/congruence.svg");
  EXPECT_EQ(all, 7u * 2u);  // two conditions: plain and none
  EXPECT_EQ(points_in(dir / "set/congruence-near.svg"), 3u * 2u);
  EXPECT_EQ(points_in(dir / "set/congruence-far.svg"), 4u * 2u);
  // One swept entry: no figure of its own besides congruence.svg.
  const Experiment one =
      load_experiment(write_ball_experiment(dir, R"({"elevations": [0], "azimuths": 2})"));
  generate_stimulus_set(one, dir / "one", options);
  testing::draw_figures(one, dir / "one", false);
  EXPECT_TRUE(fs::is_regular_file(dir / "one/congruence.svg"));
  EXPECT_FALSE(fs::exists(dir / "one/congruence-ball.svg"));
}

TEST(CongruenceSet, BadLightDirectionsAreOneLine) {
  testing::TempDir dir;
  auto error_of = [&](const std::string& directions) {
    return testing::input_error_of(
        [&] { load_experiment(write_ball_experiment(dir, directions)); });
  };
  EXPECT_NE(error_of(R"({"elevations": [90], "azimuths": 2})").find("(-90, 90)"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"elevations": [], "azimuths": 2})").find("at least one elevation"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"elevations": [10], "azimuths": 0})").find("azimuths"), std::string::npos);
  EXPECT_NE(error_of(R"({"elevations": [10], "tilt": 3})").find("tilt"), std::string::npos);
}

}  // namespace
}  // namespace countershade
