// The shading methods end to end (`lla`, `exaggerated-shading`, `radiance-scaling`,
// `light-warping`): λ = 0 is the plain render, λ > 0 sharpens the shading of features, and
// surface-mode normals do not depend on the camera.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "core/error.h"
#include "enhance/light_alignment.h"
#include "enhance/light_warping.h"
#include "enhance/lightness.h"
#include "enhance/method.h"
#include "enhance/multiscale_normals.h"
#include "enhance/radiance_scaling.h"
#include "enhance/shading_method.h"
#include "enhance/view_curvature.h"
#include "enhance/view_plan.h"
#include "render/scene_loader.h"
#include "render/shading.h"
#include "test_util.h"

namespace countershade {
namespace {

// A faceted ball (crease angle 0: every facet flat) on a grey background, lit from the upper left.
std::string faceted_ball(const std::string& eye) {
  return R"({
  "version": 1,
  "camera": {"eye": )" +
         eye + R"(, "target": [0, 0, 0], "fov": 30, "width": 96, "height": 72},
  "render": {"spp": 4},
  "objects": [{"shape": {"type": "sphere", "radius": 1, "subdivisions": 2}, "crease_angle": 0, "material": {"albedo": 0.6}}],
  "lights": [{"type": "directional", "direction": [-0.5, 0.8, 0.6], "irradiance": 2}, {"type": "ambient", "radiance": 0.1}]
})";
}

const glm::dvec3 kKeyLight =
    glm::normalize(glm::dvec3(-0.5, 0.8, 0.6));  // the direction in faceted_ball

std::shared_ptr<const View> render_ball(const testing::TempDir& dir, const std::string& eye) {
  return render_view(std::make_shared<Scene>(
      load_scene(testing::write_file(dir / "ball.json", faceted_ball(eye)))));
}

// The same ball with smooth normals (every edge below the crease angle), its key light with or
// without shadows.
std::shared_ptr<const View> render_smooth_ball(const testing::TempDir& dir, bool shadows = true) {
  std::string smooth = faceted_ball("[0, 0.5, 5]");
  smooth.replace(smooth.find("\"crease_angle\": 0"), 17, "\"crease_angle\": 90");
  const std::string key_light = "\"irradiance\": 2";
  if (!shadows)
    smooth.replace(smooth.find(key_light), key_light.size(), key_light + ", \"shadows\": false");
  return render_view(
      std::make_shared<Scene>(load_scene(testing::write_file(dir / "smooth.json", smooth))));
}

bool on_object(const View& view, size_t i) {
  return view.depth[i] > 0 && std::isfinite(view.depth[i]);
}

double lightness_at(const Image& display, const View& view, size_t i) {
  return display_pixel_to_lab(&display.pixels[3 * i], view.encoding).L;
}

// RMS difference of L* between horizontally neighbouring object pixels: how much the facets differ.
double facet_contrast(const Image& display, const View& view) {
  double sum = 0;
  size_t n = 0;
  for (int y = 0; y < display.height; ++y)
    for (int x = 1; x < display.width; ++x) {
      const size_t i = size_t(y) * display.width + x;
      if (!on_object(view, i) || !on_object(view, i - 1)) continue;
      const double d = lightness_at(display, view, i) - lightness_at(display, view, i - 1);
      sum += d * d, ++n;
    }
  return std::sqrt(sum / double(n));
}

// Standard deviation of L* over the object's pixels that the key light reaches at more than
// `min_cos` (the pixel's shading normal against the light): the lit side's range.
double lightness_spread(const Image& display, const View& view, double min_cos = -1) {
  double sum = 0, sum2 = 0;
  size_t n = 0;
  for (size_t i = 0; i < view.depth.size(); ++i) {
    if (!on_object(view, i) ||
        glm::dot(glm::dvec3(view.render.gbuffer.normal[i]), kKeyLight) < min_cos)
      continue;
    const double l = lightness_at(display, view, i);
    sum += l, sum2 += l * l, ++n;
  }
  return std::sqrt(std::max(0.0, sum2 / double(n) - (sum / double(n)) * (sum / double(n))));
}

// The largest L* step between neighbouring pixels inside the object's outline (where the outline's
// antialiasing does not mix in the background).
double largest_step(const Image& display, const View& view) {
  const int w = display.width;
  auto inside = [&](int x, int y) {
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if (!on_object(view, size_t(y + dy) * w + size_t(x + dx))) return false;
    return true;
  };
  double largest = 0;
  for (int y = 2; y + 1 < display.height; ++y)
    for (int x = 2; x + 1 < w; ++x) {
      if (!inside(x, y)) continue;
      const size_t i = size_t(y) * w + x;
      for (const auto& [nx, ny] : {std::pair{x - 1, y}, std::pair{x, y - 1}})
        if (inside(nx, ny))
          largest =
              std::max(largest, std::abs(lightness_at(display, view, i) -
                                         lightness_at(display, view, size_t(ny) * w + size_t(nx))));
    }
  return largest;
}

// The four shading methods at full strength on the smooth ball.
std::vector<std::pair<std::string, nlohmann::json>> shading_methods_on_the_smooth_ball() {
  return {{"exaggerated-shading", {{"sigma", 0.15}}},
          {"lla", {{"sigma", 0.15}}},
          {"light-warping", {{"tau", 10.0}}},
          {"radiance-scaling", {{"tau", 10.0}}}};
}

// The method prepared on the ball seen from the front, after checking that λ = 0 is the plain
// render.
std::unique_ptr<PreparedEnhancement> prepared_on_ball(const std::shared_ptr<const View>& view,
                                                      const std::string& method) {
  auto prepared = prepare_method(method, view, {{"sigma", 0.15}});
  EXPECT_EQ(prepared->compose(0.0).display.pixels, view->display.pixels) << method;
  return prepared;
}

TEST(Lla, LambdaZeroIsThePlainRenderAndLambdaOneSharpensTheFacets) {
  testing::TempDir dir;
  const auto view = render_ball(dir, "[0, 0.5, 5]");
  const auto prepared = prepared_on_ball(view, "lla");
  const Image enhanced = prepared->compose(1.0).display;
  for (float v : enhanced.pixels) ASSERT_TRUE(std::isfinite(v));
  const double plain = facet_contrast(view->display, *view),
               aligned = facet_contrast(enhanced, *view);
  EXPECT_GT(aligned, 1.3 * plain) << "plain " << plain << ", aligned " << aligned;
}

// Surface-mode normals live on the mesh: rendering from another camera (a 1° orbit) gives the
// same smoothed normal at the same surface point, to the last bit.
TEST(Lla, SurfaceNormalsDoNotDependOnTheCamera) {
  testing::TempDir a, b;
  const double t = std::acos(-1.0) / 180.0;
  const auto first = render_ball(a, "[0, 0.5, 5]");
  const auto second = render_ball(
      b, "[" + std::to_string(5 * std::sin(t)) + ", 0.5, " + std::to_string(5 * std::cos(t)) + "]");
  const MultiscaleNormals n1(first->scene, 0.15, 3), n2(second->scene, 0.15, 3);
  for (unsigned triangle : {0u, 17u, 101u, 250u}) {
    SurfacePoint p;
    p.triangle = triangle, p.b1 = 0.3, p.b2 = 0.2;
    p.shading_normal = glm::dvec3(0, 0, 1);
    for (int k = 2; k <= 3; ++k) {
      const glm::dvec3 u = n1.at(p, k), v = n2.at(p, k);
      EXPECT_LT(glm::length(u - v), 1e-6) << triangle;
      EXPECT_NEAR(glm::length(u), 1.0, 1e-9);
    }
  }
}

// The light that LLA computes at one surface point from two views of it (the second a 1° orbit of
// the first): the same in surface mode (< 1e-6), different in image mode, whose normals are
// filtered on the view's pixels.
double largest_rotation_change(const std::string& mode) {
  testing::TempDir a, b;
  const double t = std::acos(-1.0) / 180.0;
  const auto first = render_ball(a, "[0, 0.5, 5]");
  const auto second = render_ball(
      b, "[" + std::to_string(5 * std::sin(t)) + ", 0.5, " + std::to_string(5 * std::cos(t)) + "]");
  const nlohmann::json parameters = {{"sigma", mode == "image" ? 3.0 : 0.15}, {"mode", mode}};
  const PrepareContext c1 = make_context(first), c2 = make_context(second);
  NormalScales scales;
  scales.sigma = parameters["sigma"], scales.image = mode == "image";
  const auto n1 = scene_normals(c1, scales, "lla"), n2 = scene_normals(c2, scales, "lla");
  const Object& ball = first->scene->objects[0];
  const glm::dvec3& light = kKeyLight;
  const double strengths[2] = {1.0, 1.0};
  double largest = 0;
  for (unsigned triangle = 0; triangle < ball.mesh.triangles.size(); ++triangle) {
    SurfacePoint p;
    const glm::uvec3 v = ball.mesh.triangles[triangle];
    p.triangle = triangle, p.b1 = 0.3, p.b2 = 0.3;
    p.position = 0.4 * glm::dvec3(ball.mesh.positions[v.x]) +
                 0.3 * glm::dvec3(ball.mesh.positions[v.y]) +
                 0.3 * glm::dvec3(ball.mesh.positions[v.z]);
    p.shading_normal = p.geometric_normal = glm::normalize(p.position);
    if (glm::dot(p.shading_normal, glm::normalize(first->scene->camera.eye - p.position)) < 0.5)
      continue;
    glm::dvec3 l[2];
    for (int view = 0; view < 2; ++view) {
      const ShadingInputs s{p, ball.material, p.shading_normal,
                            glm::normalize((view ? second : first)->scene->camera.eye - p.position),
                            glm::dvec3(0.6)};
      glm::dvec3 n[kMaxNormalScales];
      (view ? n2 : n1)->at_shading_point(s, n);
      l[view] = align_light(light, std::span<const glm::dvec3>(n, 3), strengths, 3.0);
    }
    largest = std::max(largest, glm::length(l[0] - l[1]));
  }
  return largest;
}

TEST(Lla, ImageModeIsPlainAtLambdaZeroAndSharpensTheFacets) {
  testing::TempDir dir;
  const auto view = render_ball(dir, "[0, 0.5, 5]");
  const auto prepared = prepare_method("lla", view, {{"sigma", 3.0}, {"mode", "image"}});
  EXPECT_EQ(prepared->compose(0.0).display.pixels, view->display.pixels);
  const Image enhanced = prepared->compose(1.0).display;
  EXPECT_GT(facet_contrast(enhanced, *view), 1.3 * facet_contrast(view->display, *view));
  EXPECT_EQ(prepared->parameters()["mode"], "image");
}

TEST(Lla, TheLightRotationIsViewIndependentInSurfaceModeOnly) {
  EXPECT_LT(largest_rotation_change("surface"), 1e-6);
  EXPECT_GT(largest_rotation_change("image"), 1e-3);
}

// Two views of the same mesh (a light-direction sweep, an orbit) share their surface normals;
// another σ does not.
TEST(Lla, SurfaceNormalsAreSharedBetweenScenesWithTheSameMeshes) {
  testing::TempDir a, b;
  const auto first = render_ball(a, "[0, 0.5, 5]"), second = render_ball(b, "[0.2, 0.5, 5]");
  NormalScales scales;
  scales.sigma = 0.21;
  const auto n1 = scene_normals(make_context(first), scales, "lla");
  EXPECT_EQ(n1, scene_normals(make_context(second), scales, "lla"));
  scales.sigma = 0.22;
  EXPECT_NE(n1, scene_normals(make_context(second), scales, "lla"));
}

TEST(Lla, ParametersAreCheckedWithTheirKeys) {
  EXPECT_NE(
      testing::input_error_of([] { parse_method("lla", nlohmann::json::object()); }).find("sigma"),
      std::string::npos);
  EXPECT_NE(testing::input_error_of([] {
              parse_method("lla", {{"sigma", 0.1}, {"profile", {1, 1, 1}}});
            }).find("needs 2 values"),
            std::string::npos);
  EXPECT_NE(testing::input_error_of([] {
              parse_method("lla", {{"sigma", 0.1}, {"profile", {1, 2}}});
            }).find("[0, 1]"),
            std::string::npos);
  EXPECT_NE(testing::input_error_of([] {
              parse_method("lla", {{"sigma", 0.1}, {"kernel", 5}});
            }).find("kernel"),
            std::string::npos);
  EXPECT_NO_THROW(parse_method(
      "lla", {{"sigma", 0.1}, {"scales", 4}, {"profile", {1, 0.5, 0.2}}, {"gamma", 0}}));
  EXPECT_NE(testing::input_error_of([] {
              parse_method("lla", {{"sigma", 0.1}, {"depth_tolerance", 0.1}});
            }).find("mode image only"),
            std::string::npos);
  EXPECT_NE(testing::input_error_of([] {
              parse_method("lla", {{"sigma", 5000}, {"mode", "image"}});
            }).find("1000 pixels"),
            std::string::npos);
  EXPECT_NE(testing::input_error_of([] {
              parse_method("lla", {{"sigma", 1}, {"mode", "screen"}});
            }).find("mode"),
            std::string::npos);
}

// Exaggerated shading: λ = 0 is the plain render; λ = 1 replaces the diffuse term, which flattens
// the ball's shading where the light reaches it (its lit range shrinks) while facets still show.
TEST(ExaggeratedShading, LambdaZeroIsPlainAndFullStrengthFlattensTheLitSide) {
  testing::TempDir dir;
  const auto view = render_ball(dir, "[0, 0.5, 5]");
  const auto prepared = prepared_on_ball(view, "exaggerated-shading");
  const Image es = prepared->compose(1.0).display;
  EXPECT_LT(lightness_spread(es, *view, 0.25), 0.8 * lightness_spread(view->display, *view, 0.25));
  EXPECT_GT(facet_contrast(es, *view), 0.0);
  EXPECT_NE(testing::input_error_of([] {
              parse_method("exaggerated-shading", {{"sigma", 0.1}, {"weights", {0.5, 0.2, 0.2}}});
            }).find("must sum to 1"),
            std::string::npos);
  EXPECT_NE(testing::input_error_of([] {
              parse_method("exaggerated-shading", {{"sigma", 0.1}, {"weights", {0.5, 0.5}}});
            }).find("needs 3 values"),
            std::string::npos);
  EXPECT_NE(testing::input_error_of([] {
              parse_method("exaggerated-shading",
                           {{"sigma", 0.1}, {"weights", {0.5, 0.3, 0.2}}, {"weight_power", 0.0}});
            }).find("weight_power"),
            std::string::npos);
}

// The scales' weights default to Rusinkiewicz et al.'s k_i ∝ σ_i^−0.5 over the widths
// σ_i = σ_1·1.7^(i−1), the base coat last; weight_power 0 weighs them equally, and explicit
// weights give the same image as the equal powers they spell out.
TEST(ExaggeratedShading, TheWeightsFollowTheScalesWidthsToThePowerMinusAHalf) {
  testing::TempDir dir;
  const auto view = render_ball(dir, "[0, 0.5, 5]");
  auto record_weights = [&](const nlohmann::json& parameters) {
    return prepare_method("exaggerated-shading", view, parameters)
        ->parameters()["weights"]
        .get<std::vector<double>>();
  };
  const std::vector<double> defaults = record_weights({{"sigma", 0.15}, {"scales", 4}});
  ASSERT_EQ(defaults.size(), 4u);
  double sum = 0;
  for (int i = 0; i < 4; ++i) sum += std::pow(0.15 * std::pow(1.7, i), -0.5);
  for (int i = 0; i < 4; ++i)
    EXPECT_NEAR(defaults[size_t(i)], std::pow(0.15 * std::pow(1.7, i), -0.5) / sum, 1e-12) << i;
  EXPECT_GT(defaults[0], defaults[3]);  // the finest scale weighs most
  for (double k : record_weights({{"sigma", 0.15}, {"scales", 4}, {"weight_power", 0.0}}))
    EXPECT_NEAR(k, 0.25, 1e-15);
  const auto powered =
      prepare_method("exaggerated-shading", view, {{"sigma", 0.15}, {"scales", 4}});
  const auto spelled = prepare_method("exaggerated-shading", view,
                                      {{"sigma", 0.15}, {"scales", 4}, {"weights", defaults}});
  EXPECT_EQ(powered->compose(1.0).display.pixels, spelled->compose(1.0).display.pixels);
  const auto equal = prepare_method("exaggerated-shading", view,
                                    {{"sigma", 0.15}, {"scales", 4}, {"weight_power", 0.0}});
  EXPECT_NE(powered->compose(1.0).display.pixels, equal->compose(1.0).display.pixels);
}

// The light's terminator on a smooth ball is a smooth curve: neither the plain render nor a hook
// may draw it as the mesh's facets or as a line, whether the light casts shadows or not (its
// attached shadow stays). Shadow rays leaving the flat facets, and hooks keeping their light up to
// a per-facet terminator, left steps of 11.9 L* (plain), 29 (ES), 15.5 (LLA) and 31 (LW) between
// neighbouring pixels here; smooth terminators leave 5.9, 13.7, 9.6 and 13.3 (ES and LW turn
// steeper, as their light ramps down over a narrower band).
TEST(ShadingMethods, NoMethodDrawsTheTerminatorAsAnEdge) {
  for (bool shadows : {true, false}) {
    testing::TempDir dir;
    const auto view = render_smooth_ball(dir, shadows);
    EXPECT_LT(largest_step(view->display, *view), 7.0) << "shadows " << shadows;
    for (const auto& [method, parameters] : shading_methods_on_the_smooth_ball()) {
      const auto prepared = prepare_method(method, view, parameters);
      EXPECT_LT(largest_step(prepared->compose(1.0).display, *view), 16.0)
          << method << ", shadows " << shadows;
    }
  }
}

// The key light's dark side (shading normal facing away from it; the light casts no shadows, and
// there is no ambient light): black in the plain render. At λ = 1 local light alignment lights
// part of it, with max(0, n_1·l_1) along the facets' features, and exaggerated shading's
// half-Lambertian term all of it; light warping lights the part where the warp turns the light in
// front of the surface. With a terminator band, or under radiance scaling (which scales the light
// that arrives), it stays black.
TEST(ShadingMethods, TheOriginalLightsDarkSideIsShadedByLlaAndEs) {
  testing::TempDir dir;
  std::string scene = faceted_ball("[0, 0.5, 5]");
  scene.replace(scene.find(", {\"type\": \"ambient\", \"radiance\": 0.1}"), 38, "");
  scene.replace(scene.find("\"irradiance\": 2"), 15, "\"irradiance\": 2, \"shadows\": false");
  const auto view = render_view(
      std::make_shared<Scene>(load_scene(testing::write_file(dir / "dark.json", scene))));
  auto dark_side_lit = [&](const std::string& method, const nlohmann::json& parameters) {
    const Image image = prepare_method(method, view, parameters)->compose(1.0).display;
    size_t lit = 0, dark = 0;
    for (size_t i = 0; i < view->depth.size(); ++i) {
      // The dark side: the pixel's normal faces away from the light and none of its samples is lit.
      if (!on_object(*view, i) ||
          glm::dot(glm::dvec3(view->render.gbuffer.normal[i]), kKeyLight) > 0 ||
          view->render.radiance.pixels[3 * i] != 0.0f)
        continue;
      ++dark;
      lit += lightness_at(image, *view, i) > 1.0;
    }
    EXPECT_GT(dark, 150u);
    return double(lit) / double(dark);
  };
  EXPECT_GT(dark_side_lit("lla", {{"sigma", 0.15}}), 0.2);
  EXPECT_EQ(dark_side_lit("exaggerated-shading", {{"sigma", 0.15}}), 1.0);
  EXPECT_EQ(dark_side_lit("lla", {{"sigma", 0.15}, {"terminator_fade", 0.25}}), 0.0);
  EXPECT_EQ(dark_side_lit("exaggerated-shading", {{"sigma", 0.15}, {"terminator_fade", 0.25}}),
            0.0);
  EXPECT_GT(dark_side_lit("light-warping", {{"tau", 10.0}}), 0.05);
  EXPECT_EQ(dark_side_lit("light-warping", {{"tau", 10.0}, {"terminator_fade", 0.25}}), 0.0);
  EXPECT_EQ(dark_side_lit("radiance-scaling", {{"tau", 10.0}}), 0.0);
}

TEST(RadianceScaling, TheScaleIsOneWithoutCurvatureAndMonotoneInIt) {
  for (double delta : {0.0, 0.2, 0.5, 0.8, 1.0})
    for (double alpha : {0.1, 0.5, 1.0})
      EXPECT_NEAR(radiance_scale(0.0, delta, alpha, 1.0), 1.0, 1e-12);
  for (double delta : {0.1, 0.3, 0.7, 0.9}) {
    double previous = radiance_scale(-1.0, delta, 0.5, 1.0);
    const bool rising = radiance_scale(1.0, delta, 0.5, 1.0) > previous;
    for (int k = -99; k <= 100; ++k) {
      const double s = radiance_scale(k / 100.0, delta, 0.5, 1.0);
      EXPECT_TRUE(rising ? s >= previous : s <= previous) << delta << " " << k;
      previous = s;
    }
  }
  // Lit parts of concave places (κ < 0) get darker, as in the paper's figures.
  EXPECT_LT(radiance_scale(-0.8, 0.9, 0.8, 1.0), 1.0);
  // α is the invariant point: a reflectance δ = α is never scaled, whatever κ and γ.
  for (double alpha : {0.2, 0.5, 0.8})
    for (double kappa : {-0.9, -0.3, 0.4, 1.0})
      EXPECT_NEAR(radiance_scale(kappa, alpha, alpha, 4.0), 1.0, 1e-12);
  // On convex parts (κ > 0) darker reflectances get darker and brighter ones brighter: contrast.
  EXPECT_LT(radiance_scale(0.5, 0.2, 0.5, 4.0), 1.0);
  EXPECT_GT(radiance_scale(0.5, 0.9, 0.5, 4.0), 1.0);
}

// Mestres et al.'s Fig. 14 settings are the defaults (α = 0.5, γ = 4), and λ scales γ: γ = 4 at
// λ = 0.5 is γ = 2 at λ = 1, image for image. α outside (0, 1) is refused.
TEST(RadianceScaling, TheDefaultsAreFigure14sAndLambdaScalesGamma) {
  testing::TempDir dir;
  const auto view = render_smooth_ball(dir);
  const auto defaults = prepare_method("radiance-scaling", view, {{"tau", 10.0}});
  const auto paper =
      prepare_method("radiance-scaling", view, {{"tau", 10.0}, {"alpha", 0.5}, {"gamma", 4.0}});
  const auto half =
      prepare_method("radiance-scaling", view, {{"tau", 10.0}, {"alpha", 0.5}, {"gamma", 2.0}});
  EXPECT_EQ(defaults->compose(1.0).display.pixels, paper->compose(1.0).display.pixels);
  EXPECT_EQ(paper->compose(0.5).display.pixels, half->compose(1.0).display.pixels);
  EXPECT_NE(paper->compose(1.0).display.pixels, half->compose(1.0).display.pixels);
  const auto other_alpha =
      prepare_method("radiance-scaling", view, {{"tau", 10.0}, {"alpha", 0.2}});
  EXPECT_NE(other_alpha->compose(1.0).display.pixels, paper->compose(1.0).display.pixels);
  for (double alpha : {0.0, 1.0, -0.5})
    EXPECT_NE(testing::input_error_of([&] {
                parse_method("radiance-scaling", {{"alpha", alpha}});
              }).find("alpha"),
              std::string::npos);
}

// A smooth ball is convex everywhere: its curvature is positive inside its outline.
TEST(RadianceScaling, CurvatureIsPositiveOnAConvexBallAndLambdaZeroIsPlain) {
  testing::TempDir dir;
  const auto view = render_smooth_ball(dir);
  const ViewCurvature curvature(*view, 10.0);
  const Image& kappa = curvature.pixels();
  EXPECT_GT(kappa.at(48, 36), 0.0f);
  EXPECT_GT(kappa.at(40, 30), 0.0f);
  EXPECT_EQ(kappa.at(2, 2), 0.0f);  // background
  // The outline too: a curvature of 0 there would draw a ring of plain shading around the object.
  const GBuffer& g = view->render.gbuffer;
  int outline = 0;
  for (int y = 1; y + 1 < g.height; ++y)
    for (int x = 1; x + 1 < g.width; ++x) {
      if (g.object[g.index(x, y)] < 0) continue;
      const bool at_outline = g.object[g.index(x - 1, y)] < 0 || g.object[g.index(x + 1, y)] < 0 ||
                              g.object[g.index(x, y - 1)] < 0 || g.object[g.index(x, y + 1)] < 0;
      outline += at_outline;
      EXPECT_GT(kappa.at(x, y), 0.0f) << x << "," << y << (at_outline ? " (outline)" : "");
    }
  EXPECT_GT(outline, 20);
  const auto prepared = prepare_method("radiance-scaling", view, {{"tau", 10.0}});
  EXPECT_EQ(prepared->compose(0.0).display.pixels, view->display.pixels);
  EXPECT_NE(prepared->compose(1.0).display.pixels, view->display.pixels);
}

double angle_between(const glm::dvec3& a, const glm::dvec3& b) {
  return std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0));
}

// The warp keeps λ = 0 and κ = 0 as they are, turns the light towards r on convex parts and away
// on concave ones, stays in the plane of the light and r, and never leaves [0, π] from r.
TEST(LightWarping, TheWarpTurnsTheLightTowardsOrAwayFromTheReflectedViewAndStaysInItsPlane) {
  const glm::dvec3 r = glm::normalize(glm::dvec3(0.1, 0.2, 1.0));
  for (double azimuth : {0.0, 1.0, 2.5, 4.0})
    for (double polar : {0.05, 0.6, 1.5, 2.4, 3.1}) {
      const glm::dvec3 wi =
          glm::normalize(glm::dvec3(std::sin(polar) * std::cos(azimuth),
                                    std::sin(polar) * std::sin(azimuth), std::cos(polar)));
      EXPECT_LT(glm::length(warp_light(wi, r, 0.7, 0.0) - wi), 1e-12);
      EXPECT_LT(glm::length(warp_light(wi, r, 0.0, 3.0) - wi), 1e-12);
      const double before = angle_between(wi, r);
      double previous = before;
      for (double lambda : {0.5, 1.0, 2.0, 4.0}) {
        const glm::dvec3 convex = warp_light(wi, r, 0.8, lambda),
                         concave = warp_light(wi, r, -0.8, lambda);
        EXPECT_NEAR(glm::length(convex), 1.0, 1e-12);
        EXPECT_NEAR(glm::dot(convex, glm::cross(wi, r)), 0.0, 1e-12);  // in the plane of wi and r
        EXPECT_LT(angle_between(convex, r), previous);                 // monotone in λ
        EXPECT_GT(angle_between(concave, r), before);
        EXPECT_LE(angle_between(concave, r), std::acos(-1.0) + 1e-12);
        previous = angle_between(convex, r);
      }
    }
}

// The warp as light_warping.h defines it, with the C library's functions.
glm::dvec3 reference_warp(const glm::dvec3& wi, const glm::dvec3& r, double kappa, double lambda) {
  const double cos_angle = std::clamp(glm::dot(wi, r), -1.0, 1.0);
  const glm::dvec3 across = wi - cos_angle * r;
  if (glm::length(across) < 1e-12) return wi;
  const double angle = std::acos(cos_angle), e = std::exp(-lambda * kappa);
  const double warped = angle * e / (1 + (e - 1) * angle / std::acos(-1.0));
  return std::cos(warped) * r + std::sin(warped) * glm::normalize(across);
}

// Many warps at once (vector lanes) give warp_light's bits, and both follow the definition.
TEST(LightWarping, ManyAtOnceEqualOneAtATimeAndFollowTheDefinition) {
  testing::with_and_without_avx512([] {
    std::mt19937 random(5);
    std::normal_distribution<double> gauss;
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    auto unit = [&] {
      return glm::normalize(glm::dvec3(gauss(random), gauss(random), gauss(random)));
    };
    std::vector<glm::dvec3> wi, r, out(150);
    std::vector<double> kappa;
    for (size_t k = 0; k < out.size(); ++k) {
      r.push_back(unit());
      wi.push_back(k % 11 == 3 ? r.back()
                               : (k % 11 == 7 ? -r.back() : unit()));  // along r, opposite it
      kappa.push_back(uniform(random));
    }
    warp_lights(wi, r, kappa, 2.5, out.data());
    double worst = 0;
    for (size_t k = 0; k < out.size(); ++k) {
      const glm::dvec3 one = warp_light(wi[k], r[k], kappa[k], 2.5);
      for (int c = 0; c < 3; ++c) ASSERT_EQ(out[k][c], one[c]) << k;
      worst = std::max(worst, glm::length(one - reference_warp(wi[k], r[k], kappa[k], 2.5)));
    }
    EXPECT_LT(worst, 1e-12);
  });
}

TEST(LightWarping, LambdaZeroIsPlainAndAWarpChangesTheConvexBall) {
  testing::TempDir dir;
  const auto view = render_smooth_ball(dir);
  const auto prepared = prepare_method("light-warping", view, {{"tau", 10.0}});
  EXPECT_EQ(prepared->compose(0.0).display.pixels, view->display.pixels);
  const Image warped = prepared->compose(2.0).display;
  for (float v : warped.pixels) ASSERT_TRUE(std::isfinite(v));
  EXPECT_NE(warped.pixels, view->display.pixels);
  EXPECT_NE(testing::input_error_of([] {
              parse_method("light-warping", {{"gamma", 1.0}});
            }).find("gamma"),
            std::string::npos);
}

// The amount of warping α defaults to Mestres et al.'s Fig. 14 (16.62), and λ scales it: α at
// λ = 0.5 is α/2 at λ = 1, image for image.
TEST(LightWarping, TheAmountOfWarpingIsAlphaTimesLambda) {
  testing::TempDir dir;
  const auto view = render_smooth_ball(dir);
  const auto defaults = prepare_method("light-warping", view, {{"tau", 10.0}});
  const auto paper = prepare_method("light-warping", view, {{"tau", 10.0}, {"alpha", 16.62}});
  const auto half = prepare_method("light-warping", view, {{"tau", 10.0}, {"alpha", 8.31}});
  EXPECT_EQ(defaults->compose(0.3).display.pixels, paper->compose(0.3).display.pixels);
  EXPECT_EQ(paper->compose(0.5).display.pixels, half->compose(1.0).display.pixels);
  EXPECT_NE(paper->compose(1.0).display.pixels, half->compose(1.0).display.pixels);
  EXPECT_NE(testing::input_error_of([] {
              parse_method("light-warping", {{"alpha", -1.0}});
            }).find("alpha"),
            std::string::npos);
}

}  // namespace
}  // namespace countershade
