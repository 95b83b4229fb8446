// Scale against depth: the halo width of one profile, of a synthetic layer attached to a receding
// ground (width ∝ 1/depth, slope −1) and of one of fixed screen size (slope 0), and an edge probe
// set that records and plots them.

#include "measures/scale_against_depth.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>

#include "measures/flicker.h"
#include "render/scene_loader.h"
#include "stimuli/set_test_util.h"
#include "test_util.h"

namespace countershade {
namespace {

namespace fs = std::filesystem;

TEST(HaloWidth, AnExponentialFallOffGivesItsWidthFromThePeak) {
  for (double offset : {0.0, 0.3, 0.9})
    for (double width : {1.7, 4.0, 12.5}) {
      std::vector<double> d, v;
      for (int i = 0; i < 60; ++i)
        d.push_back(offset + i), v.push_back(3 * std::exp(-(offset + i) / width));
      EXPECT_NEAR(halo_width(d, v), width, 1e-9) << offset << " " << width;
    }
  const std::vector<double> d{0, 1, 2}, flat{1, 1, 1}, none{0, 0, 0};
  EXPECT_TRUE(std::isnan(halo_width(d, flat)));  // never falls to 1/e
  EXPECT_TRUE(std::isnan(halo_width(d, none)));
}

const char* kEdgeGround = R"({"version": 1,
  "camera": {"eye": [0, 1.0, 3.0], "target": [0, 0, -6], "fov": 40, "width": 256, "height": 192},
  "render": {"spp": 1},
  "objects": [{"name": "ground", "shape": {"type": "plane", "size": 16, "subdivisions": 2},
               "transform": {"translate": [0, 0, -6]}}],
  "lights": [{"type": "directional", "direction": [0, 1, 0], "irradiance": 1, "shadows": false}]})";

const std::vector<double> kEdges = {-3, -2, -1, 0, 1, 2, 3};

// The world point of every ground pixel (NaN elsewhere).
std::vector<glm::dvec3> world_points(const View& v) {
  const CameraRays rays(v.scene->camera);
  std::vector<glm::dvec3> out(v.depth.size(), glm::dvec3(NAN));
  for (int y = 0; y < v.height(); ++y)
    for (int x = 0; x < v.width(); ++x) {
      const size_t i = size_t(y) * v.width() + x;
      if (!std::isfinite(v.depth[i])) continue;
      out[i] = rays.point_at_depth(x + 0.5, y + 0.5, v.depth[i]);
    }
  return out;
}

// A halo of world width W on both sides of every edge, opposite signs: attached to the ground.
std::vector<float> attached_layer(const View& v, double W) {
  const std::vector<glm::dvec3> p = world_points(v);
  std::vector<float> layer(p.size(), 0.0f);
  for (size_t i = 0; i < p.size(); ++i) {
    if (std::isnan(p[i].x)) continue;
    const double k = std::round(p[i].x);
    layer[i] = float((p[i].x > k ? 8 : -8) * std::exp(-std::abs(p[i].x - k) / W));
  }
  return layer;
}

// A halo of w pixels along each edge's normal in the image: fixed to the screen.
std::vector<float> screen_layer(const View& v, double w) {
  const CameraRays rays(v.scene->camera);
  const std::vector<glm::dvec3> p = world_points(v);
  std::vector<float> layer(p.size(), 0.0f);
  for (size_t i = 0; i < p.size(); ++i) {
    if (std::isnan(p[i].x)) continue;
    const double k = std::round(p[i].x);
    const glm::dvec2 a = rays.film_position({k, 0, -2}), b = rays.film_position({k, 0, -10});
    const glm::dvec2 n = glm::normalize(glm::dvec2(b.y - a.y, a.x - b.x));
    const glm::dvec2 pixel(double(i % size_t(v.width())) + 0.5,
                           double(i / size_t(v.width())) + 0.5);
    layer[i] = float((p[i].x > k ? 8 : -8) * std::exp(-std::abs(glm::dot(pixel - a, n)) / w));
  }
  return layer;
}

TEST(ScaleAgainstDepth, ASyntheticHaloOfKnownWidthIsMeasuredAtThreeDepths) {
  testing::TempDir dir;
  const auto view = geometry_view(
      std::make_shared<const Scene>(load_scene(testing::write_file(dir / "g.json", kEdgeGround))),
      1);
  const double W = 0.05, focal = 96 / std::tan(20 * std::numbers::pi / 180);
  const std::vector<HaloSample> samples =
      halo_samples({view->scene->camera, view->depth, attached_layer(*view, W)}, kEdges, 1);
  int checked = 0;
  for (double depth : {3.0, 6.0, 10.0}) {
    const HaloSample* nearest = nullptr;  // the edge straight ahead, x = 0, upright in the image
    for (const HaloSample& s : samples)
      if (s.edge_x == 0 &&
          (!nearest || std::abs(s.depth - depth) < std::abs(nearest->depth - depth)))
        nearest = &s;
    ASSERT_NE(nearest, nullptr);
    EXPECT_NEAR(nearest->width_px, W * focal / nearest->depth, 0.2)
        << "at depth " << nearest->depth;
    checked += std::abs(nearest->depth - depth) < 0.5;
  }
  EXPECT_EQ(checked, 3);
  EXPECT_NEAR(depth_slope(samples).slope, -1.0, 0.03);
  const std::vector<HaloSample> fixed =
      halo_samples({view->scene->camera, view->depth, screen_layer(*view, 4.0)}, kEdges, 1);
  EXPECT_NEAR(depth_slope(fixed).slope, 0.0, 0.03);
  for (const HaloSample& s : fixed) {
    if (s.edge_x == 0 && s.depth < 8) {
      EXPECT_NEAR(s.width_px, 4.0, 0.2) << s.depth;
    }
  }
}

TEST(ScaleAgainstDepth, AProbeSetRecordsWidthsAndSlopesAndPlotsThem) {
  testing::TempDir dir;
  testing::write_file(
      dir / "ground.json",
      std::string(kEdgeGround)
          .replace(
              std::string(kEdgeGround).find("\"shape\""), 0,
              R"("material": {"texture": {"pattern": "stripes", "size": 64, "stripes": 2}, "texture_repeat": 8}, )"));
  const fs::path experiment = testing::write_file(dir / "experiment.json", R"({
    "version": 1, "name": "probe", "seed": 1, "lambda": {"min": 0, "max": 1, "step": 1},
    "scenes": [{"name": "probe", "file": "ground.json", "edge_probe": {"edges_x": [-3, -2, -1, 0, 1, 2, 3]}}],
    "methods": [{"method": "usm2d", "sigma_px": [3]}]})");
  const Experiment e = load_experiment(experiment);
  generate_stimulus_set(e, dir / "set", testing::with_jobs(2));
  testing::draw_figures(e, dir / "set", false);
  const OrderedJson manifest = testing::manifest_json(dir / "set");
  for (const auto& s : manifest["stimuli"]) {
    if (s["method"] != "usm2d" || s["lambda"] != 1.0) continue;
    EXPECT_GT(s["depth_slope_samples"].get<int>(), 20);
    EXPECT_NEAR(s["depth_slope"].get<double>(), 0.0, 0.15);  // usm2d keeps one screen size
  }
  EXPECT_TRUE(fs::exists(dir / "set" / "scale-against-depth-probe.svg"));
  EXPECT_NE(testing::read_file(dir / "set" / "scale-against-depth.csv").find("probe,usm2d,1,0,"),
            std::string::npos);
}

TEST(ScaleAgainstDepth, AProbeNeedsEdgesInOrderOnAStillScene) {
  testing::TempDir dir;
  testing::write_file(dir / "ground.json", kEdgeGround);
  const auto load = [&](const std::string& probe) {
    return load_experiment(testing::write_file(dir / "e.json", R"({"version": 1, "name": "p",
      "lambda": {"min": 0, "max": 1, "step": 1},
      "scenes": [{"name": "probe", "file": "ground.json", "edge_probe": )" +
                                                                   probe + R"(}],
      "methods": [{"method": "usm2d", "sigma_px": [3]}]})"));
  };
  EXPECT_THROW(load(R"({"edges_x": [1, 0]})"), InputError);
  EXPECT_THROW(load(R"({"edges_x": []})"), InputError);
  EXPECT_THROW(load(R"({"edges": [0]})"), InputError);
  EXPECT_NO_THROW(load(R"({"edges_x": [0, 1]})"));
}

}  // namespace
}  // namespace countershade
