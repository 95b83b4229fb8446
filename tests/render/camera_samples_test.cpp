#include "render/camera_samples.h"

#include <gtest/gtest.h>

#include <set>

#include "render/renderer.h"
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

// A render that traces its camera samples ahead (one with a ring-sampled vertex signal at a fixed
// count) gives the pixels of one that traces them in the pixel pass: the same positions, for Sobol
// sampling, the independent sampler's Latin hypercubes and the single centre sample.
TEST(CameraSamples, TheHitsTracedAheadAreThePixelPassOwn) {
  testing::TempDir dir;
  for (const char* settings : {R"({"spp": 8})", R"({"spp": 5, "sampler": "independent"})", R"({"spp": 1})"}) {
    const Scene scene = two_objects(dir, settings);
    const RayTracer tracer(scene);
    ASSERT_NE(trace_camera_samples(scene, tracer, 2), nullptr) << settings;
    RenderOptions with;
    with.vertex_radiance = true;  // with ring points, traces the samples ahead
    with.ring_samples = 3;
    with.vertex_needs.assign(scene.objects.size(), VertexNeed{0.3, 2, 3});
    const RenderResult ahead = render(scene, tracer, with), plain = render(scene, tracer, RenderOptions{});
    EXPECT_EQ(ahead.radiance.pixels, plain.radiance.pixels) << settings;
    EXPECT_EQ(ahead.rays.primary, plain.rays.primary) << settings << ": every camera ray counted once";
  }
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
