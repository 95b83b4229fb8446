#include "render/renderer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>

#include "enhance/usm3d.h"
#include "render/camera.h"
#include "render/camera_samples.h"
#include "render/scene_loader.h"
#include "render/shading.h"
#include "test_util.h"

namespace countershade {
namespace {

Scene scene_from(const testing::TempDir& dir, const std::string& json) {
  return load_scene(testing::write_file(dir / "scene.json", json));
}

// Analytic reference: an orthographic camera looks down -z at a unit sphere. Where the ray
// through a pixel centre meets the ideal sphere, the Lambertian radiance is ρ/π · E · max(0, n·l).
TEST(Renderer, LambertianSphereMatchesAnalyticRadiance) {
  testing::TempDir dir;
  Scene scene = scene_from(dir, R"({
    "version": 1,
    "camera": {"eye": [0, 0, 5], "target": [0, 0, 0], "projection": "orthographic", "height_world": 2.4,
               "width": 121, "height": 121},
    "render": {"spp": 1},
    "objects": [{"shape": {"type": "sphere", "radius": 1, "subdivisions": 6},
                 "material": {"albedo": [0.6, 0.5, 0.4]}}],
    "lights": [{"type": "directional", "direction": [1, 1, 1], "irradiance": [2, 3, 4]}]
  })");
  RayTracer tracer(scene);
  RenderResult result = render(scene, tracer);
  const glm::dvec3 albedo(0.6, 0.5, 0.4), E(2, 3, 4), l = glm::normalize(glm::dvec3(1, 1, 1));
  int checked = 0;
  for (int y = 0; y < 121; ++y)
    for (int x = 0; x < 121; ++x) {
      double sx = (2.0 * (x + 0.5) / 121 - 1.0) * 1.2, sy = (1.0 - 2.0 * (y + 0.5) / 121) * 1.2;
      double r2 = sx * sx + sy * sy;
      if (r2 > 0.81) continue;  // keep away from the tessellated silhouette
      glm::dvec3 n(sx, sy, std::sqrt(1.0 - r2));
      double cos_l = glm::dot(n, l);
      for (int c = 0; c < 3; ++c) {
        double expected = albedo[c] / std::numbers::pi * E[c] * std::max(0.0, cos_l);
        double actual = result.radiance.at(x, y, c);
        if (cos_l > 0.1) {
          EXPECT_NEAR(actual, expected, 0.01 * expected) << x << "," << y;
        } else if (cos_l < -0.05) {
          EXPECT_EQ(actual, 0.0f) << x << "," << y;
        }
      }
      checked += cos_l > 0.1;
    }
  EXPECT_GT(checked, 3000);
}

// Furnace test: a closed convex object inside a uniform white environment reflects exactly its
// albedo.
TEST(Renderer, FurnaceReproducesAlbedo) {
  testing::TempDir dir;
  for (std::string sampling : {"cosine", "importance"}) {
    Scene scene = scene_from(dir, R"({
      "version": 1,
      "camera": {"eye": [0, 0, 4], "target": [0, 0, 0], "fov": 40, "width": 48, "height": 48},
      "render": {"spp": 16, "seed": 9},
      "objects": [{"shape": {"type": "sphere", "radius": 1, "subdivisions": 5}, "material": {"albedo": 0.6}}],
      "lights": [{"type": "environment", "constant": 1, "samples": 16, "sampling": ")" +
                                      sampling + R"("}]
    })");
    RayTracer tracer(scene);
    RenderResult result = render(scene, tracer);
    double sum = 0;
    int pixels = 0;
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 48; ++x) {
        if (result.gbuffer.object[result.gbuffer.index(x, y)] != 0) continue;
        // Interior pixels only: silhouette pixels mix in the environment.
        bool interior = true;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx)
            interior &= result.gbuffer.object[result.gbuffer.index(std::clamp(x + dx, 0, 47),
                                                                   std::clamp(y + dy, 0, 47))] == 0;
        if (!interior) continue;
        double v = result.radiance.at(x, y, 1);
        if (sampling == "cosine") {
          EXPECT_NEAR(v, 0.6, 0.02 * 0.6) << x << "," << y;
        }
        sum += v;
        ++pixels;
      }
    ASSERT_GT(pixels, 500);
    EXPECT_FLOAT_EQ(result.radiance.at(0, 0, 0), 1.0f);  // the background sees the environment
    EXPECT_NEAR(sum / pixels, 0.6, 0.02 * 0.6) << sampling;
  }
}

// An environment map read from an EXR file lights the scene like the built-in constant one.
TEST(Renderer, EnvironmentMapFromAnExrFile) {
  testing::TempDir dir;
  write_image(dir / "white.exr", Image(32, 16, 3, 1.0f));
  Scene scene = scene_from(dir, R"({
    "version": 1,
    "camera": {"eye": [0, 0, 4], "target": [0, 0, 0], "fov": 30, "width": 16, "height": 16},
    "render": {"spp": 4},
    "objects": [{"shape": {"type": "sphere", "radius": 1, "subdivisions": 4}, "material": {"albedo": 0.5}}],
    "lights": [{"type": "environment", "file": "white.exr", "samples": 16, "sampling": "cosine"}]
  })");
  RayTracer tracer(scene);
  RenderResult result = render(scene, tracer);
  EXPECT_NEAR(result.radiance.at(8, 8, 0), 0.5f, 0.01f);  // furnace: the albedo
  EXPECT_FLOAT_EQ(result.radiance.at(0, 0, 1), 1.0f);     // the camera sees the map
}

TEST(Renderer, PointInShadowReceivesNoDirectLight) {
  testing::TempDir dir;
  // A slab 1 unit above the ground; light from 45° in +x, so the shadow falls 1 unit towards -x.
  Scene scene = scene_from(dir, R"({
    "version": 1,
    "camera": {"eye": [0, 6, 6], "target": [0, 0, 0], "width": 64, "height": 48},
    "objects": [
      {"name": "ground", "shape": {"type": "plane", "size": 8, "subdivisions": 8}, "material": {"albedo": 0.5}},
      {"name": "slab", "shape": {"type": "box", "size": [1, 0.1, 1]}, "transform": {"translate": [0, 1, 0]}}
    ],
    "lights": [{"type": "directional", "direction": [1, 1, 0], "irradiance": 2},
               {"type": "point", "position": [3, 3, 0], "intensity": 5}]
  })");
  scene.point_lights.clear();  // first the directional light alone
  RayTracer tracer(scene);
  Shader shader(scene, tracer);
  RayCounts counts;
  auto ground_point = [&](double x, double z) {
    SurfacePoint sp;
    sp.position = {x, 0, z};
    sp.geometric_normal = sp.shading_normal = {0, 1, 0};
    sp.object = 0;
    return sp;
  };
  const glm::dvec3 up(0, 1, 0);
  Sampler random(SamplingMode::sobol, 1, kDomainPixel, 0, 0);
  EXPECT_EQ(shader.radiance(ground_point(-1.0, 0.0), up, false, random, counts), glm::dvec3(0.0));
  EXPECT_EQ(shader.radiance(ground_point(-1.4, 0.4), up, false, random, counts), glm::dvec3(0.0));
  glm::dvec3 lit = shader.radiance(ground_point(1.5, 0.0), up, false, random, counts);
  EXPECT_NEAR(lit.x, 0.5 / std::numbers::pi * 2.0 * std::sqrt(0.5), 1e-9);
  EXPECT_GT(counts.shadow, 0u);
  // "shadows": false: the shadowed point gets the same light as the lit one, and no shadow ray is
  // cast.
  scene.directional_lights[0].shadows = false;
  Shader unshadowed(scene, tracer);
  RayCounts none;
  EXPECT_EQ(unshadowed.radiance(ground_point(-1.0, 0.0), up, false, random, none), lit);
  EXPECT_EQ(none.shadow, 0u);
}

TEST(Renderer, SameSeedGivesByteIdenticalPngsAtOneAndTwoThreads) {
  testing::TempDir dir;
  std::string mesh = testing::mesh_path("spot.obj").string();
  Scene scene = scene_from(dir, R"({
    "version": 1,
    "camera": {"eye": [1.5, 1.2, 2.0], "target": [0, 0.3, 0], "width": 56, "height": 40},
    "render": {"spp": 4, "seed": 42},
    "objects": [
      {"shape": {"type": "plane", "size": 4, "subdivisions": 4}},
      {"mesh": ")" + mesh + R"(", "fit": true, "material": {"specular": {"model": "cook-torrance"}}}
    ],
    "lights": [
      {"type": "point", "position": [1, 3, 1], "intensity": 8, "radius": 0.2, "samples": 2},
      {"type": "environment", "sky": {}, "samples": 2},
      {"type": "ambient", "radiance": 0.1, "occlusion_distance": 0.5, "samples": 2}
    ]
  })");
  RayTracer tracer(scene);
  auto png_bytes = [&](int threads, const std::string& name) {
    RenderOptions options;
    options.threads = threads;
    Image display = encode_for_display(render(scene, tracer, options).radiance,
                                       scene.display.exposure(), scene.display.encoding);
    write_image(dir / name, display);
    return testing::read_file(dir / name);
  };
  std::string one = png_bytes(1, "one.png"), two = png_bytes(2, "two.png"),
              again = png_bytes(2, "again.png");
  EXPECT_EQ(one, two);
  EXPECT_EQ(two, again);
  scene.settings.seed = 43;
  EXPECT_NE(png_bytes(2, "other.png"), one) << "a different seed should change the noise";
}

TEST(Renderer, AFixedCountRenderWithoutItsNoiseEstimateGivesTheSamePixels) {
  testing::TempDir dir;
  Scene scene = scene_from(dir, R"({
    "version": 1,
    "camera": {"eye": [1.5, 1.2, 2.0], "target": [0, 0.3, 0], "width": 40, "height": 30},
    "render": {"spp": 4, "seed": 5},
    "objects": [{"shape": {"type": "sphere", "radius": 0.5}}],
    "lights": [{"type": "point", "position": [1, 3, 1], "intensity": 8, "radius": 0.2, "samples": 2}]
  })");
  RayTracer tracer(scene);
  RenderOptions options;
  options.threads = 2;
  const RenderResult with = render(scene, tracer, options);
  options.estimate_noise = false;
  const RenderResult without = render(scene, tracer, options);
  EXPECT_EQ(with.radiance.pixels, without.radiance.pixels);
  EXPECT_EQ(with.spp, without.spp);
  double noise = 0;
  for (float n : with.noise) noise += n;
  EXPECT_GT(noise, 0.0);  // the soft shadow and the sphere's edge are noisy at 4 spp
  for (float n : without.noise) ASSERT_EQ(n, 0.0f);
}

// A sphere on a plane under a point light with a radius (a soft shadow) and ambient occlusion, at
// `size` pixels, with `render` as its render block.
Scene soft_shadow_scene(const testing::TempDir& dir, const std::string& size,
                        const std::string& render) {
  return scene_from(dir, R"({
    "version": 1,
    "camera": {"eye": [1.5, 1.2, 2.0], "target": [0, 0.3, 0], )" +
                             size + R"(},
    "render": )" + render + R"(,
    "objects": [
      {"shape": {"type": "plane", "size": 4, "subdivisions": 8}},
      {"shape": {"type": "sphere", "radius": 0.4, "subdivisions": 3}, "transform": {"translate": [0, 0.4, 0]}}
    ],
    "lights": [
      {"type": "point", "position": [1, 3, 1], "intensity": 8, "radius": 0.3, "samples": 1},
      {"type": "ambient", "radiance": 0.1, "occlusion_distance": 0.5, "samples": 1}
    ]
  })");
}

// Adaptive sampling decides per pixel and per vertex how many samples to take; those decisions,
// like the samples, must not depend on how the work is split over threads.
TEST(Renderer, AdaptiveSamplingIsByteIdenticalAtOneAndTwoThreads) {
  testing::TempDir dir;
  Scene scene = soft_shadow_scene(dir, R"("width": 48, "height": 36)", R"({"seed": 7})");
  RayTracer tracer(scene);
  auto run = [&](int threads) {
    RenderOptions options;
    options.threads = threads;
    options.vertex_radiance = true;
    return render(scene, tracer, options);
  };
  RenderResult one = run(1), two = run(2);
  EXPECT_EQ(one.radiance.pixels, two.radiance.pixels);
  EXPECT_EQ(one.spp, two.spp);
  EXPECT_EQ(one.noise, two.noise);
  EXPECT_EQ(one.vertices.front, two.vertices.front);
  EXPECT_EQ(one.vertices.front_noise, two.vertices.front_noise);
  EXPECT_GT(one.sampling.pixels.max, one.sampling.pixels.min)
      << "the soft shadow should need more samples";
  EXPECT_TRUE(one.sampling.budget_met)
      << one.sampling.stopped_by << " " << one.sampling.pixels.mean;
}

// The vertex signal's error estimate (from its two replicates) against the spread of the signal
// between seeds, at fixed counts: --spp 8 with ring points (each of a vertex's points takes 1
// sample, the points split between the replicates by turns), --spp 16 (2 per point), and --spp 4
// without ring points (2 per vertex, the least: with one, a replicate would be empty). The
// estimate pools the 1-ring and counts the ring's spatial variation as error, so it may run high,
// but not low and not far off (1.2-1.26 times the spread here).
TEST(Renderer, TheVertexErrorEstimateAtAFixedCountFollowsTheSpreadBetweenSeeds) {
  testing::TempDir dir;
  constexpr int kSeeds = 12;
  for (auto [spp, ring] : {std::pair{8, 3}, std::pair{16, 3}, std::pair{4, 0}}) {
    Scene scene = soft_shadow_scene(dir, R"("width": 32, "height": 24)",
                                    R"({"spp": )" + std::to_string(spp) + "}");
    RayTracer tracer(scene);
    const Exposure exposure = scene.display.exposure();
    const size_t nv = scene.objects[1].mesh.vertex_count();  // the sphere
    std::vector<double> sum(nv, 0.0), sum2(nv, 0.0), estimate(nv, 0.0);
    for (int seed = 1; seed <= kSeeds; ++seed) {
      scene.settings.seed = uint64_t(seed);
      RenderOptions options;
      options.vertex_radiance = true;
      options.ring_samples = ring;
      const RenderResult result = render(scene, tracer, options);
      for (size_t v = 0; v < nv; ++v) {
        const double L =
            cielab_lightness(display_luminance(glm::dvec3(result.vertices.front[1][v]), exposure));
        sum[v] += L;
        sum2[v] += L * L;
        estimate[v] +=
            result.vertices.front_noise[1][v] * result.vertices.front_noise[1][v] / kSeeds;
      }
    }
    double spread = 0, estimated = 0;  // mean squares over the vertices
    for (size_t v = 0; v < nv; ++v) {
      spread += (sum2[v] - sum[v] * sum[v] / kSeeds) / (kSeeds - 1) / double(nv);
      estimated += estimate[v] / double(nv);
    }
    const double ratio = std::sqrt(estimated / spread);
    EXPECT_GT(ratio, 0.8) << "spp " << spp << ", ring " << ring << ": RMS spread "
                          << std::sqrt(spread);
    EXPECT_LT(ratio, 2.0) << "spp " << spp << ", ring " << ring << ": RMS spread "
                          << std::sqrt(spread);
  }
}

// A noise budget over the image rather than every pixel: the pixels whose noise costs most samples
// (the soft shadow, the occluded corners) carry more of it, so the render takes fewer samples; its
// RMS estimate stays within the target (with its tenth in hand), and no pixel's passes the p99
// bound over 2.576.
TEST(Renderer, ANoiseBudgetOverTheImageTakesFewerSamplesForTheSameRms) {
  testing::TempDir dir;
  auto scene_with = [&](const std::string& allocation) {
    return soft_shadow_scene(
        dir, R"("width": 64, "height": 48)",
        R"({"seed": 7, "noise": {"target": 0.5, "allocation": ")" + allocation + R"("}})");
  };
  const auto rms = [](const std::vector<float>& v) {
    double sum = 0;
    for (float x : v) sum += double(x) * x;
    return std::sqrt(sum / double(v.size()));
  };
  const Scene per_pixel = scene_with("pixel"), per_image = scene_with("image");
  const RenderResult a = render(per_pixel, RayTracer(per_pixel), {}),
                     b = render(per_image, RayTracer(per_image), {});
  EXPECT_LT(b.sampling.pixels.mean, 0.8 * a.sampling.pixels.mean);
  EXPECT_LE(rms(a.noise), 0.5);
  EXPECT_LE(rms(b.noise), 0.5);
  EXPECT_GT(rms(b.noise), rms(a.noise));
  EXPECT_GT(*std::max_element(b.noise.begin(), b.noise.end()), 0.6)
      << "some pixel carries more than the target";
  EXPECT_TRUE(b.sampling.budget_met);
}

// The smoothed signal and the gain of two renders' vertex signals agree exactly at every vertex of
// a triangle a pixel can read: one that a camera sample hits (a fixed count), or that meets the
// view's frustum (a budget).
void expect_same_smoothing_in_view(const Scene& scene, const RayTracer& tracer,
                                   const RenderResult& a, const RenderResult& b, int iterations) {
  const CameraRays camera(scene.camera);
  const std::shared_ptr<const CameraHits> hits = trace_camera_samples(scene, tracer, 2);
  for (unsigned o = 0; o < scene.objects.size(); ++o) {
    const Object& object = scene.objects[o];
    SmoothingWidth width;
    width.iterations = iterations;
    const SurfaceContrast sa = surface_contrast(object, a.vertices.front[o], scene.display, width);
    const SurfaceContrast sb = surface_contrast(object, b.vertices.front[o], scene.display, width);
    size_t compared = 0;
    for (size_t i = 0; i < object.mesh.triangle_count(); ++i) {
      const glm::uvec3& t = object.mesh.triangles[i];
      const auto& p = object.mesh.positions;
      if (hits ? !hits->triangles_hit(o)[i] : !camera.may_see(p[t.x], p[t.y], p[t.z])) continue;
      for (uint32_t v : {t.x, t.y, t.z}) {
        ASSERT_EQ(sa.smooth_lightness[v], sb.smooth_lightness[v])
            << "object " << o << " vertex " << v;
        ASSERT_EQ(sa.gain_factor[v], sb.gain_factor[v]) << "object " << o << " vertex " << v;
        ++compared;
      }
    }
    EXPECT_GT(compared, 0u);
  }
}

// The vertex pass shades only what can reach a pixel: vertices within the smoothing's support
// (and one ring past it, or past the refinement's) of a triangle in view. On a large, finely
// divided ground most of it lies outside the view; the smoothed signal and the gain at every vertex
// of a triangle in view are still exactly those of shading every vertex, with a fixed count and
// with the budget.
TEST(Renderer, TheVertexPassSkipsWhatNoPixelCanDependOnWithoutChangingWhatOneDoes) {
  testing::TempDir dir;
  Scene scene = scene_from(dir, R"({
    "version": 1,
    "camera": {"eye": [0.3, 0.8, 1.6], "target": [0, 0.3, 0], "fov": 35, "width": 40, "height": 30},
    "render": {"seed": 3},
    "objects": [
      {"shape": {"type": "plane", "size": 10, "subdivisions": 60}},
      {"shape": {"type": "sphere", "radius": 0.3, "subdivisions": 3}, "transform": {"translate": [0, 0.3, 0]}}
    ],
    "lights": [{"type": "point", "position": [1, 3, 1], "intensity": 8, "radius": 0.3, "samples": 1}]
  })");
  RayTracer tracer(scene);
  constexpr int kSupport = 4;
  for (std::optional<int> spp : {std::optional<int>(8), std::optional<int>()}) {
    scene.settings.spp = spp;
    auto run = [&](int support) {
      RenderOptions options;
      options.vertex_radiance = true;
      options.ring_samples = 3;
      options.vertex_needs.assign(scene.objects.size(), VertexNeed{0.3, 2, support});
      return render(scene, tracer, options);
    };
    const RenderResult culled = run(kSupport), all = run(-1);
    size_t skipped = 0;  // ground vertices left unshaded (value 0)
    for (size_t v = 0; v < all.vertices.front[0].size(); ++v)
      skipped += culled.vertices.front[0][v] == glm::vec3(0.0f) &&
                 all.vertices.front[0][v] != glm::vec3(0.0f);
    EXPECT_GT(skipped, all.vertices.front[0].size() / 2) << "most of the ground is out of view";
    expect_same_smoothing_in_view(scene, tracer, culled, all, kSupport);
  }
}

// A vertex placed on the ray through the centre pixel of an odd-sized orthographic view
// must get the same radiance from the vertex path as from the pixel path.
TEST(Renderer, VertexRadianceEqualsPixelRadianceAtAProjectedVertex) {
  testing::TempDir dir;
  Scene scene = scene_from(dir, R"({
    "version": 1,
    "camera": {"eye": [0, 0, 5], "target": [0, 0, 0], "projection": "orthographic", "width": 33, "height": 33},
    "render": {"spp": 1},
    "objects": [
      {"shape": {"type": "sphere", "radius": 1, "subdivisions": 3},
       "material": {"albedo": [0.7, 0.6, 0.5], "specular": {"model": "blinn-phong", "color": 0.2, "shininess": 20}}},
      {"shape": {"type": "box", "size": [0.4, 0.4, 0.4]}, "transform": {"translate": [1.6, 1.4, 1.2]}}
    ],
    "lights": [
      {"type": "directional", "direction": [0.3, 0.8, 0.5], "irradiance": 2},
      {"type": "point", "position": [2.5, 2.2, 2.0], "intensity": 4},
      {"type": "ambient", "radiance": 0.05}
    ]
  })");
  RayTracer tracer(scene);
  const TriangleMesh& sphere = scene.objects[0].mesh;
  int compared = 0;
  for (unsigned v : {5u, 17u, 40u, 77u, 120u, 311u}) {
    glm::dvec3 p = sphere.positions[v], n = glm::normalize(p);
    if (std::abs(n.y) > 0.9) continue;
    // Aim a hair (1e-6) beside the vertex: a ray through the exact float vertex may slip between
    // its triangles, and 1e-6 moves barycentrics by ~1e-5, far below the tolerance.
    glm::dvec3 aside = 1e-6 * glm::normalize(glm::cross(n, glm::dvec3(0, 1, 0)));
    scene.camera.eye = p + aside + 3.0 * n;
    scene.camera.target = p + aside;
    RenderOptions options;
    options.vertex_radiance = true;  // view-dependent: per camera
    RenderResult result = render(scene, tracer, options);
    const auto& vertex_radiance = result.vertices.front;
    ASSERT_EQ(result.gbuffer.object[result.gbuffer.index(16, 16)], 0);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(result.radiance.at(16, 16, c), vertex_radiance[0][v][c],
                  1e-4 * (1.0 + vertex_radiance[0][v][c]))
          << "vertex " << v;
    ++compared;
  }
  EXPECT_GE(compared, 4);
}

TEST(Renderer, GBufferHoldsDepthNormalAndIds) {
  testing::TempDir dir;
  Scene scene = scene_from(dir, R"({
    "version": 1,
    "camera": {"eye": [0, 0, 5], "target": [0, 0, 0], "projection": "orthographic", "width": 21, "height": 21},
    "render": {"spp": 1},
    "objects": [{"shape": {"type": "box", "size": [1, 1, 1]}}]
  })");
  RayTracer tracer(scene);
  RenderResult result = render(scene, tracer);
  const GBuffer& g = result.gbuffer;
  size_t centre = g.index(10, 10), corner = g.index(0, 0);
  EXPECT_NEAR(g.depth[centre], 4.5f, 1e-5f);
  EXPECT_NEAR(g.normal[centre].z, 1.0f, 1e-6f);
  EXPECT_EQ(g.object[centre], 0);
  EXPECT_GE(g.triangle[centre], 0);
  EXPECT_EQ(g.object[corner], -1);
  EXPECT_TRUE(std::isinf(g.depth[corner]));
  EXPECT_EQ(result.radiance.at(0, 0, 0), 0.0f);  // no environment, no background: black
}

}  // namespace
}  // namespace countershade
