// Animation paths: keys are hit exactly, Catmull–Rom is C¹, bad paths are refused with the key
// path, and a posed scene renders like the same scene written still.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>
#include <limits>

#include "core/image.h"
#include "enhance/view.h"
#include "enhance/view_plan.h"
#include "measures/perspective_coherence.h"
#include "render/camera.h"
#include "render/scene_animation.h"
#include "render/scene_loader.h"
#include "test_util.h"

namespace countershade {
namespace {

const std::vector<double> kTimes = {0.0, 0.3, 1.1, 1.5, 2.0};
const std::vector<glm::dvec3> kValues = {{0, 0, 0}, {1, 2, -1}, {3, -1, 0.5}, {2, 2, 2}, {5, 0, 1}};

TEST(Track, KeysAreHitExactly) {
  for (Interpolation mode : {Interpolation::linear, Interpolation::catmull_rom}) {
    const Track track(kTimes, kValues, mode);
    for (size_t k = 0; k < kTimes.size(); ++k) EXPECT_EQ(track.at(kTimes[k]), kValues[k]) << k;
    EXPECT_EQ(track.at(-1.0), kValues.front());  // held before the first key
    EXPECT_EQ(track.at(9.0), kValues.back());    // and after the last
  }
  EXPECT_EQ(Track(kTimes, kValues, Interpolation::linear).at(0.15), glm::dvec3(0.5, 1, -0.5));
}

// The one-sided derivatives agree at every interior key (and the value is continuous there).
TEST(Track, CatmullRomIsContinuouslyDifferentiable) {
  const Track track(kTimes, kValues, Interpolation::catmull_rom);
  const double h = 1e-6;
  for (size_t k = 1; k + 1 < kTimes.size(); ++k) {
    const double t = kTimes[k];
    const glm::dvec3 left = (track.at(t) - track.at(t - h)) / h,
                     right = (track.at(t + h) - track.at(t)) / h;
    EXPECT_LT(glm::length(left - right), 1e-4 * (1 + glm::length(left))) << "key " << k;
    EXPECT_LT(glm::length(track.at(t - h) - track.at(t)), 1e-4);
  }
  // A linear path has corners there: the test can tell.
  const Track linear(kTimes, kValues, Interpolation::linear);
  const double t = kTimes[1];
  EXPECT_GT(
      glm::length((linear.at(t) - linear.at(t - h)) / h - (linear.at(t + h) - linear.at(t)) / h),
      1.0);
}

TEST(Track, FewKeysOrTimesThatDoNotIncreaseAreRefused) {
  EXPECT_THROW(Track({0.0}, {{1, 1, 1}}, Interpolation::linear), std::invalid_argument);
  EXPECT_THROW(Track({0.0, 1.0, 1.0}, {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}, Interpolation::linear),
               std::invalid_argument);
  EXPECT_THROW(Track({0.0, 2.0, 1.0}, {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}, Interpolation::linear),
               std::invalid_argument);
}

std::string scene_json(const std::string& eye, const std::string& animation) {
  return R"({"version": 1,
    "camera": {"eye": )" +
         eye + R"(, "target": [0, 0.3, 0], "fov": 35, "width": 48, "height": 36},
    "render": {"spp": 2},
    "objects": [{"name": "ground", "shape": {"type": "plane", "size": 6}},
                {"name": "box", "shape": {"type": "box", "size": [0.6, 0.6, 0.6]}, "transform": {"translate": [0, 0.3, 0]}}],
    "lights": [{"type": "directional", "direction": [0.4, 1, 0.3], "irradiance": 2.5}])" +
         (animation.empty() ? "" : ", \"animation\": " + animation) + "}";
}

const char* kOrbit = R"({"duration": 1.5, "fps": 2,
  "camera": {"eye": {"times": [0, 1], "values": [[0, 1, 4], [4, 1, 0]], "interpolation": "catmull-rom"}},
  "lights": [{"light": 0, "direction": {"times": [0, 1], "values": [[0.4, 1, 0.3], [0, 2, 0]]}}],
  "objects": [{"name": "box", "translate": {"times": [0, 1], "values": [[0, 0, 0], [1, 0, 0]]}}]})";

TEST(SceneAnimation, ThePosedSceneMovesCameraLightsAndObjects) {
  testing::TempDir dir;
  const Scene base =
      load_scene(testing::write_file(dir / "s.json", scene_json("[0, 1, 4]", kOrbit)));
  ASSERT_TRUE(base.animation);
  EXPECT_EQ(base.animation->frame_count(), 3);
  const Scene end = scene_at(base, 1.0);
  EXPECT_EQ(end.camera.eye, glm::dvec3(4, 1, 0));
  EXPECT_LT(glm::length(end.directional_lights[0].direction - glm::dvec3(0, 1, 0)),
            1e-12);  // normalised
  const glm::dvec3 moved =
      glm::dvec3(end.objects[1].mesh.positions[0]) - glm::dvec3(base.objects[1].mesh.positions[0]);
  EXPECT_LT(glm::length(moved - glm::dvec3(1, 0, 0)), 1e-6);
  EXPECT_EQ(end.objects[0].mesh.positions, base.objects[0].mesh.positions);  // the ground stays
}

// A scaled object keeps its surface graph, so the edge lengths that turn σ into steps are measured
// again at its posed positions (a usm3d sequence smooths the grown box over fewer steps).
TEST(SceneAnimation, AScaledObjectsEdgeLengthsAreMeasuredAgain) {
  testing::TempDir dir;
  const char* grow = R"({"duration": 1, "fps": 2,
    "objects": [{"name": "box", "scale": {"times": [0, 1], "values": [[1, 1, 1], [2, 2, 2]]}}]})";
  const Scene base = load_scene(testing::write_file(dir / "s.json", scene_json("[0, 1, 4]", grow)));
  const Scene end = scene_at(base, 1.0);
  const std::vector<double>& before = base.objects[1].surface.mean_edge_length;
  const std::vector<double>& after = end.objects[1].surface.mean_edge_length;
  ASSERT_EQ(before.size(), 1u);
  ASSERT_EQ(after.size(), 1u);
  EXPECT_NEAR(after[0], 2 * before[0], 1e-6);
  EXPECT_EQ(end.objects[0].surface.mean_edge_length,
            base.objects[0].surface.mean_edge_length);  // the ground stays
}

TEST(SceneAnimation, BadPathsNameTheKey) {
  testing::TempDir dir;
  auto error = [&](const std::string& animation) {
    return testing::input_error_of([&] {
      load_scene(testing::write_file(dir / "s.json", scene_json("[0, 1, 4]", animation)));
    });
  };
  EXPECT_NE(
      error(
          R"({"camera": {"eye": {"times": [0, 0.5, 0.5], "values": [[0,1,4], [1,1,4], [2,1,4]]}}})")
          .find("animation.camera.eye.times: times must increase strictly (key 3)"),
      std::string::npos);
  EXPECT_NE(error(R"({"camera": {"fov": {"times": [0], "values": [30]}}})")
                .find("animation.camera.fov.times: a path needs at least two keys"),
            std::string::npos);
  EXPECT_NE(
      error(
          R"({"objects": [{"name": "cube", "translate": {"times": [0, 1], "values": [[0,0,0], [1,0,0]]}}]})")
          .find("animation.objects[0].name: no object of the scene is called 'cube'"),
      std::string::npos);
  EXPECT_NE(
      error(
          R"({"lights": [{"light": 0, "position": {"times": [0, 1], "values": [[0,0,0], [1,0,0]]}}]})")
          .find("animation.lights[0].position: applies to a point light only"),
      std::string::npos);
  EXPECT_NE(
      error(
          R"({"duration": 1, "camera": {"eye": {"times": [0, 2], "values": [[0,1,4], [1,1,4]]}}})")
          .find("animation.camera.eye.times: must lie in [0, duration]"),
      std::string::npos);
  EXPECT_NE(
      error(R"({"camera": {"eye": {"times": [0, 1], "values": [[0,1,4], [1,1,4]], "ease": 1}}})")
          .find("animation.camera.eye.ease: unknown key"),
      std::string::npos);
}

// Frame 2 of the orbit (t = 1) is the scene with every path at its last key, written still.
TEST(SceneAnimation, RenderFramesWritesNumberedFramesLikeStillScenes) {
  testing::TempDir dir;
  testing::write_file(dir / "orbit.json", scene_json("[0, 1, 4]", kOrbit));
  const auto r = testing::run_cli("render " + (dir / "orbit.json").string() + " -o " +
                                  (dir / "f.png").string() + " --frames 1:2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "f-0000.png"));
  ASSERT_TRUE(std::filesystem::exists(dir / "f-0001.png"));
  std::string still = scene_json("[4, 1, 0]", "");
  still.replace(still.find("\"direction\": [0.4, 1, 0.3]"), 26, "\"direction\": [0, 1, 0]");
  still.replace(still.find("\"translate\": [0, 0.3, 0]"), 24, "\"translate\": [1, 0.3, 0]");
  testing::write_file(dir / "still.json", still);
  ASSERT_EQ(testing::run_cli("render " + (dir / "still.json").string() + " -o " +
                             (dir / "still.png").string())
                .exit_code,
            0);
  EXPECT_EQ(testing::read_file(dir / "f-0002.png"), testing::read_file(dir / "still.png"));
  EXPECT_NE(testing::read_file(dir / "f-0001.png"), testing::read_file(dir / "still.png"));
  const auto bad = testing::run_cli("render " + (dir / "still.json").string() + " -o " +
                                    (dir / "x.png").string() + " --frames 0:0");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.output.find("--frames: " + (dir / "still.json").string() + " has no animation"),
            std::string::npos)
      << bad.output;
}

// A pattern painted on the box (a function of its own x) as a per-pixel layer at time t.
std::vector<float> painted_box(const View& v, double t) {
  const CameraRays rays(v.scene->camera);
  std::vector<float> out(v.depth.size(), 0.0f);
  for (size_t i = 0; i < out.size(); ++i) {
    if (v.render.gbuffer.object[i] != 1) continue;
    const Ray r =
        rays.ray(double(i % size_t(v.width())) + 0.5, double(i / size_t(v.width())) + 0.5);
    const glm::dvec3 p =
        r.origin + r.direction * (double(v.depth[i]) / glm::dot(r.direction, rays.forward()));
    out[i] =
        float(5 * std::sin(2 * 3.141592653589793 * (p.x - t) / 0.5));  // the box moves by (t, 0, 0)
  }
  return out;
}

// A box slides across a still camera: carried along its motion, a pattern painted on it
// reprojects onto itself; left where it was, it does not.
TEST(SceneAnimation, PointsOfAMovingObjectAreCarriedAlongItsMotion) {
  testing::TempDir dir;
  const Scene base = load_scene(
      testing::write_file(dir / "s.json", scene_json("[0, 1, 4]", R"({"duration": 1, "fps": 10,
    "objects": [{"name": "box", "translate": {"times": [0, 1], "values": [[0, 0, 0], [1, 0, 0]]}}]})")));
  const auto a = render_view(std::make_shared<Scene>(scene_at(base, 0.3)));
  const auto b = render_view(std::make_shared<Scene>(scene_at(base, 0.4)));
  const CarryPoint carry = [&](const glm::dvec3& p, int object) {
    return object < 0 ? p : carry_point(base, size_t(object), 0.3, 0.4, p);
  };
  const auto pa = painted_box(*a, 0.3), pb = painted_box(*b, 0.4);
  const Reprojection carried = reprojection_rms(*a, pa, *b, pb, carry),
                     left = reprojection_rms(*a, pa, *b, pb);
  EXPECT_LT(glm::length(carry_point(base, 1, 0.3, 0.4, {0, 0, 0}) - glm::dvec3(0.1, 0, 0)), 1e-12);
  EXPECT_EQ(carry_point(base, 0, 0.3, 0.4, {2, 0, 1}),
            glm::dvec3(2, 0, 1));  // the ground has no path
  EXPECT_LT(carried.rms, 0.2) << "left behind: " << left.rms;
  EXPECT_GT(left.rms, 1.0) << "carried: " << carried.rms;
}

// usm3d's vertex signal is tied to the surface: with a fixed sample count, a diffuse scene seen
// from two cameras gives every vertex that both shade the same radiance, so a static point does
// not shimmer.
TEST(SceneAnimation, TheVertexSignalOfAStaticDiffuseSceneDoesNotDependOnTheCamera) {
  testing::TempDir dir;
  const Scene base =
      load_scene(testing::write_file(dir / "s.json", scene_json("[0, 1, 4]", kOrbit)));
  Scene a = base, b = base;
  a.animation.reset();
  b.animation.reset();
  b.camera.eye = {1.5, 1.2, 3.6};
  const ViewPlan plan = plan_for("usm3d", {{"sigma", 0.1}}, 1.0);
  const auto va = render_view(std::make_shared<Scene>(a), plan, {}),
             vb = render_view(std::make_shared<Scene>(b), plan, {});
  ASSERT_EQ(va->render.vertices.front.size(), 2u);
  // Vertices that no pixel of a view can depend on are not shaded in it (value 0); every vertex
  // both views shade has the same value.
  for (size_t o = 0; o < 2; ++o) {
    const auto &fa = va->render.vertices.front[o], &fb = vb->render.vertices.front[o];
    ASSERT_EQ(fa.size(), fb.size());
    size_t compared = 0;
    for (size_t v = 0; v < fa.size(); ++v) {
      if (fa[v] == glm::vec3(0.0f) || fb[v] == glm::vec3(0.0f)) continue;
      EXPECT_EQ(fa[v], fb[v]) << "object " << o << " vertex " << v;
      ++compared;
    }
    EXPECT_GT(compared, fa.size() / 2) << "object " << o;
  }
}

TEST(Flicker, TheUnenhancedRenderHasNoneAndABadRangeIsOneLine) {
  testing::TempDir dir;
  testing::write_file(dir / "orbit.json", scene_json("[0, 1, 4]", kOrbit));
  const auto r = testing::run_cli("flicker " + (dir / "orbit.json").string() + " --csv " +
                                  (dir / "f.csv").string() + " --maps " + (dir / "maps").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("2 frame pairs, mean flicker 0.0000 L*"), std::string::npos) << r.output;
  EXPECT_EQ(testing::count_lines(testing::read_file(dir / "f.csv")), 3);
  EXPECT_TRUE(std::filesystem::exists(dir / "maps/flicker-0001.png"));
  EXPECT_TRUE(std::filesystem::exists(dir / "maps/flicker-0002.png"));
  EXPECT_TRUE(std::filesystem::exists(dir / "maps/plain-0002.png"));
  // --width alone scales the frames and keeps the scene's 4:3.
  const auto small =
      testing::run_cli("flicker " + (dir / "orbit.json").string() +
                       " --width 24 --frames 0:1 --maps " + (dir / "small").string());
  ASSERT_EQ(small.exit_code, 0) << small.output;
  const Image map = read_image(dir / "small/flicker-0001.png");
  EXPECT_EQ(map.width, 24);
  EXPECT_EQ(map.height, 18);
  const auto bad = testing::run_cli("flicker " + (dir / "orbit.json").string() + " --frames 1:1");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(testing::count_lines(bad.output), 1) << bad.output;
  const auto unknown =
      testing::run_cli("flicker " + (dir / "orbit.json").string() + " --object nothing");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.output.find("--object"), std::string::npos) << unknown.output;
  EXPECT_EQ(testing::count_lines(unknown.output), 1) << unknown.output;
}

// --without leaves an object out with its motion; the paths of the objects after it still find
// them (the box becomes the first object), and it is then no object to measure.
TEST(Flicker, AnObjectLeftOutTakesItsMotionAlong) {
  testing::TempDir dir;
  testing::write_file(dir / "orbit.json", scene_json("[0, 1, 4]", kOrbit));
  const std::string base = "flicker " + (dir / "orbit.json").string();
  const auto r =
      testing::run_cli(base + " --without ground --object box --csv " + (dir / "f.csv").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("box: largest change 0.00 code levels"), std::string::npos) << r.output;
  const auto gone = testing::run_cli(base + " --without box --object box");
  EXPECT_EQ(gone.exit_code, 2);
  EXPECT_NE(gone.output.find("--object: "), std::string::npos) << gone.output;
  EXPECT_EQ(testing::count_lines(gone.output), 1) << gone.output;
  const auto unknown = testing::run_cli(base + " --without nothing");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.output.find("--without: "), std::string::npos) << unknown.output;
  // With both objects out nothing is measured: an error, not a flicker of 0.
  testing::write_file(dir / "alone.json", R"({"version": 1,
    "camera": {"eye": [0, 1, 4], "target": [0, 0.3, 0], "fov": 35, "width": 16, "height": 12},
    "objects": [{"name": "box", "shape": {"type": "box", "size": [0.6, 0.6, 0.6]}}],
    "lights": [{"type": "directional", "direction": [0.4, 1, 0.3], "irradiance": 2.5}],
    "animation": {"duration": 1, "fps": 2,
                  "objects": [{"name": "box", "translate": {"times": [0, 1], "values": [[0, 0, 0], [1, 0, 0]]}}]}})");
  const auto empty =
      testing::run_cli("flicker " + (dir / "alone.json").string() + " --without box");
  EXPECT_EQ(empty.exit_code, 2);
  EXPECT_NE(empty.output.find("no surface point is seen in two consecutive frames"),
            std::string::npos)
      << empty.output;
  EXPECT_EQ(testing::count_lines(empty.output), 1) << empty.output;
}

// --scale-px compares the layers blurred: none without enhancement, and the plain render's own
// error shrinks, since blurring takes out the pixel-scale detail the resampling cannot carry.
TEST(Flicker, AtAScaleTheLayersAreComparedBlurred) {
  testing::TempDir dir;
  testing::write_file(dir / "orbit.json", scene_json("[0, 1, 4]", kOrbit));
  const auto r = testing::run_cli("flicker " + (dir / "orbit.json").string() +
                                  " --scale-px 2 --csv " + (dir / "f.csv").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("at 2 px: 0.0000 L*"), std::string::npos) << r.output;
  EXPECT_NE(testing::read_file(dir / "f.csv").find("plain_at_scale_lstar"), std::string::npos);
  double plain = 0, at_scale = 0;
  ASSERT_EQ(std::sscanf(r.output.substr(r.output.find("own reprojection ")).c_str(),
                        "own reprojection %lf", &plain),
            1);
  ASSERT_EQ(std::sscanf(r.output.substr(r.output.find("(plain ")).c_str(), "(plain %lf", &at_scale),
            1);
  EXPECT_GT(plain, 0.0);
  EXPECT_LT(at_scale, plain) << r.output;
}

// An object's change in code levels: none without enhancement, some under usm2d (whose halo
// around the box moves with the screen, not with the box).
TEST(Flicker, AnObjectsChangeIsCountedInCodeLevels) {
  testing::TempDir dir;
  testing::write_file(dir / "orbit.json", scene_json("[0, 1, 4]", kOrbit));
  const std::string base = "flicker " + (dir / "orbit.json").string() + " --object box --csv " +
                           (dir / "f.csv").string();
  const auto plain = testing::run_cli(base);
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_NE(plain.output.find("box: largest change 0.00 code levels"), std::string::npos)
      << plain.output;
  EXPECT_NE(testing::read_file(dir / "f.csv").find("object_max_levels"), std::string::npos);
  const auto usm2d = testing::run_cli(base + " --method usm2d --sigma-px 3 --lambda 3");
  ASSERT_EQ(usm2d.exit_code, 0) << usm2d.output;
  const auto at = usm2d.output.find("box: largest change ");
  ASSERT_NE(at, std::string::npos) << usm2d.output;
  EXPECT_GT(std::stod(usm2d.output.substr(at + 20)), 1.0) << usm2d.output;
}

// The stable flicker counts only pixels whose plain L* reprojects within the tolerance (and that
// counted at all): the RMS of 1 and 3 here; none at all gives 0, not NaN.
TEST(Flicker, TheStableRmsLeavesOutPixelsWhosePlainRenderChanges) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<float> layer = {1.0f, 2.0f, nan, 3.0f}, plain = {0.0f, 0.5f, 0.0f, 0.05f};
  const Reprojection stable = rms_where_stable(layer, plain, 0.1);
  EXPECT_EQ(stable.pixels, 2u);
  EXPECT_NEAR(stable.rms, std::sqrt(5.0), 1e-12);
  EXPECT_EQ(rms_where_stable(layer, plain, -1.0).rms, 0.0);
  EXPECT_NEAR(rms_where_stable(layer, plain, 1.0).rms, std::sqrt(14.0 / 3.0), 1e-12);
}

// Through the command: a tolerance above every change counts every pixel (the full flicker), and
// --bits 16 measures stimuli without the 8-bit steps, whose rounding differs from frame to frame.
TEST(Flicker, TheStableFlickerWithALooseToleranceIsTheFullOne) {
  testing::TempDir dir;
  testing::write_file(dir / "orbit.json", scene_json("[0, 1, 4]", kOrbit));
  const std::string base =
      "flicker " + (dir / "orbit.json").string() + " --method usm2d --sigma-px 3 --lambda 2";
  const auto loose =
      testing::run_cli(base + " --stable 100 --object box --csv " + (dir / "f.csv").string());
  ASSERT_EQ(loose.exit_code, 0) << loose.output;
  double full = 0, stable = 0;
  ASSERT_EQ(std::sscanf(loose.output.substr(loose.output.find("mean flicker ")).c_str(),
                        "mean flicker %lf", &full),
            1);
  ASSERT_EQ(std::sscanf(loose.output.substr(loose.output.find("within 100: ")).c_str(),
                        "within 100: %lf", &stable),
            1);
  EXPECT_GT(full, 0.1);
  EXPECT_DOUBLE_EQ(stable, full);
  EXPECT_NE(testing::read_file(dir / "f.csv").find("flicker_stable_lstar"), std::string::npos);
  EXPECT_NE(testing::read_file(dir / "f.csv").find("object_stable_p99_levels"), std::string::npos);
  double object_max = 0, object_p99 = 0, stable_max = 0, stable_p99 = 0;
  ASSERT_EQ(
      std::sscanf(
          loose.output.substr(loose.output.find("box: largest change ")).c_str(),
          "box: largest change %lf code levels (p99 %lf, worst pair), where stable %lf (p99 %lf)",
          &object_max, &object_p99, &stable_max, &stable_p99),
      4)
      << loose.output;
  EXPECT_GT(object_max, 1.0);
  EXPECT_EQ(stable_max, object_max);
  EXPECT_EQ(stable_p99, object_p99);
  const auto tight = testing::run_cli(base + " --stable 0.2 --bits 16");
  ASSERT_EQ(tight.exit_code, 0) << tight.output;
  ASSERT_EQ(std::sscanf(tight.output.substr(tight.output.find("within 0.2: ")).c_str(),
                        "within 0.2: %lf", &stable),
            1);
  EXPECT_LT(stable, full) << tight.output;
  EXPECT_EQ(testing::run_cli(base + " --bits 12").exit_code, 2);
}

}  // namespace
}  // namespace countershade
