// The ray recorder behind the renderer-against-Embree measurement (bench/render_bench.cpp,
// BM_RayRatio): attached to a render, it keeps each ray the render counts, the image stays the
// same bits, and the replay through Embree alone finds what the tracer's own queries find.

#include "render/ray_recorder.h"

#include <gtest/gtest.h>

#include "core/parallel.h"
#include "render/ray_tracer.h"
#include "render/renderer.h"
#include "render/scene_loader.h"
#include "test_util.h"

namespace countershade {
namespace {

TEST(RayRecorder, KeepsEveryRayOfARenderAndChangesNothing) {
  Scene scene = load_scene(testing::source_dir() / "experiments/scenes/bunny-sky.json");
  scene.camera.width = 48;
  scene.camera.height = 36;
  scene.settings.spp = 2;
  RayTracer tracer(scene);
  const RenderResult plain = render(scene, tracer);
  RayRecorder recorder;
  tracer.record_rays(&recorder);
  const RenderResult recorded_render = render(scene, tracer);
  tracer.record_rays(nullptr);
  const std::vector<RecordedRay> rays = recorder.take();
  EXPECT_EQ(recorded_render.radiance.pixels, plain.radiance.pixels);
  EXPECT_EQ(rays.size(), plain.rays.primary + plain.rays.shadow);
  EXPECT_GT(plain.rays.shadow, plain.rays.primary);
  EXPECT_TRUE(recorder.take().empty()) << "taken once";

  size_t closest = 0, expected_hits = 0;
  for (const RecordedRay& r : rays) {
    const glm::dvec3 o(r.origin[0], r.origin[1], r.origin[2]),
        d(r.direction[0], r.direction[1], r.direction[2]);
    closest += r.closest;
    expected_hits += r.closest ? tracer.intersect(o, d, r.tnear, r.tfar).has_value()
                               : tracer.occluded(o, d, r.tnear, r.tfar);
  }
  EXPECT_EQ(closest, plain.rays.primary);
  EXPECT_EQ(tracer.replay(rays), expected_hits);
  EXPECT_GT(expected_hits, rays.size() / 10);
}

}  // namespace
}  // namespace countershade
