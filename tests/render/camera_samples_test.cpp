#include "render/camera_samples.h"

#include <gtest/gtest.h>

#include <random>
#include <set>

#include "render/camera.h"
#include "render/renderer.h"
#include "render/scene_loader.h"
#include "test_util.h"

namespace countershade {
namespace {

Scene two_objects(const testing::TempDir& dir, const std::string& render) {
  return load_scene(testing::write_file(dir / "scene.json", R"({
    "version": 1,
    "camera": {"eye": [0.3, 0.8, 1.6], "target": [0, 0.3, 0], "fov": 35, "width": 40, "height": 30},
    "render": )" + render + R"(,
    "objects": [
      {"shape": {"type": "plane", "size": 10, "subdivisions": 60}},
      {"shape": {"type": "sphere", "radius": 0.3, "subdivisions": 3}, "transform": {"translate": [0, 0.3, 0]}}
    ],
    "lights": [{"type": "point", "position": [1, 3, 1], "intensity": 8, "radius": 0.3, "samples": 1}]
  })"));
}

// A render that traces its camera samples ahead (every render at a fixed count: plain, and with a
// ring-sampled vertex signal, whose vertex pass then shades fewer vertices) gives the pixels of one
// that traces them in the pixel pass: the same positions, for Sobol sampling, the independent
// sampler's Latin hypercubes and the single centre sample.
TEST(CameraSamples, TheHitsTracedAheadAreThePixelPassOwn) {
  testing::TempDir dir;
  for (const char* settings : {R"({"spp": 8})", R"({"spp": 5, "sampler": "independent"})",
                               R"({"spp": 1})", R"({"spp": 11})"}) {
    const Scene scene = two_objects(dir, settings);
    const RayTracer tracer(scene);
    ASSERT_NE(trace_camera_samples(scene, tracer, 2), nullptr) << settings;
    RenderOptions rings;
    rings.vertex_radiance = true;
    rings.ring_samples = 3;
    rings.vertex_needs.assign(scene.objects.size(), VertexNeed{0.3, 2, 3});
    for (const RenderOptions& options : {RenderOptions{}, rings}) {
      RenderOptions in_pixel_pass = options;
      in_pixel_pass.trace_ahead = false;
      const RenderResult ahead = render(scene, tracer, options),
                         traced = render(scene, tracer, in_pixel_pass);
      EXPECT_EQ(ahead.radiance.pixels, traced.radiance.pixels) << settings;
      EXPECT_EQ(ahead.rays.primary, traced.rays.primary)
          << settings << ": every camera ray counted once";
    }
  }
}

// A packet of rays finds each ray's own hit: the triangle and the barycentrics of the ray traced
// alone, misses included, in full packets and in the last, partial one.
TEST(CameraSamples, APacketHitsWhatItsRaysHitAlone) {
  testing::TempDir dir;
  const Scene scene = two_objects(dir, R"({"spp": 8})");
  const RayTracer tracer(scene);
  const CameraRays camera(scene.camera);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> x(-5.0, 45.0), y(-5.0, 35.0);  // some rays leave the frame
  size_t hits = 0, misses = 0;
  for (int packet = 0; packet < 200; ++packet) {
    const int count = 1 + packet % RayTracer::kPacket;
    glm::dvec3 origins[RayTracer::kPacket], directions[RayTracer::kPacket];
    std::optional<Hit> together[RayTracer::kPacket];
    for (int k = 0; k < count; ++k) {
      const Ray ray = camera.ray(x(random), y(random));
      origins[k] = ray.origin;
      directions[k] = k % 5 == 4 ? -ray.direction : ray.direction;  // backwards: into the sky
    }
    tracer.intersect_packet(count, origins, directions, together);
    for (int k = 0; k < count; ++k) {
      const std::optional<Hit> alone = tracer.intersect(origins[k], directions[k]);
      ASSERT_EQ(together[k].has_value(), alone.has_value()) << packet << " " << k;
      if (!alone) {
        ++misses;
        continue;
      }
      ++hits;
      EXPECT_EQ(together[k]->object, alone->object);
      EXPECT_EQ(together[k]->triangle, alone->triangle);
      EXPECT_EQ(together[k]->b1, alone->b1);
      EXPECT_EQ(together[k]->b2, alone->b2);
      EXPECT_EQ(together[k]->t, alone->t);
    }
  }
  EXPECT_GT(hits, 300u);
  EXPECT_GT(misses, 50u);
}

// With one sample per pixel, at its centre, the triangles hit are those the G-buffer's centre rays
// hit; with eight, more of them (the small, far triangles of the ground that centres miss).
TEST(CameraSamples, TheTrianglesHitAreThoseTheSamplesSee) {
  testing::TempDir dir;
  for (int spp : {1, 8}) {
    const Scene scene = two_objects(dir, R"({"spp": )" + std::to_string(spp) + "}");
    const RayTracer tracer(scene);
    const GBuffer g = render_gbuffer(scene, tracer, 2);
    const auto hits = trace_camera_samples(scene, tracer, 2);
    for (unsigned o = 0; o < scene.objects.size(); ++o) {
      std::set<uint32_t> centre, sampled;
      for (size_t p = 0; p < g.object.size(); ++p)
        if (g.object[p] == int32_t(o)) centre.insert(uint32_t(g.triangle[p]));
      const std::vector<uint8_t>& hit = hits->triangles_hit(o);
      for (uint32_t t = 0; t < hit.size(); ++t)
        if (hit[t]) sampled.insert(t);
      EXPECT_FALSE(centre.empty());
      if (spp == 1) {
        EXPECT_EQ(sampled, centre) << "object " << o;
      } else {
        EXPECT_GT(sampled.size(), centre.size()) << "object " << o;
      }
    }
  }
}

// Without a fixed count the samples are not known ahead.
TEST(CameraSamples, NoneUnderANoiseBudget) {
  testing::TempDir dir;
  const Scene scene = two_objects(dir, "{}");
  EXPECT_EQ(trace_camera_samples(scene, RayTracer(scene), 2), nullptr);
}

}  // namespace
}  // namespace countershade
