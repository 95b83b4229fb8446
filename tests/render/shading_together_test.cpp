// Shading several points together (their shadow rays traced in shared packets) gives each point
// what shading it alone gives.

#include <gtest/gtest.h>

#include <optional>
#include <vector>

#include "core/random.h"
#include "render/camera.h"
#include "render/rich_scene.h"
#include "render/shading.h"

namespace countershade {
namespace {

// Every kind of light, soft shadows, ambient occlusion, a texture and a glossy lobe
// (testing::kRichScene): points of the ball, the box and the textured floor, seen from the camera,
// some from pixels that see the sky (no point).
TEST(ShadingTogether, EachPointGetsWhatItsOwnShadingGives) {
  testing::TempDir dir;
  const auto scene = testing::rich_scene(dir);
  const RayTracer tracer(*scene);
  const Shader shader(*scene, tracer);
  const CameraRays camera(scene->camera);
  std::vector<SurfacePoint> points;
  std::vector<glm::dvec3> towards_viewer;
  for (int y = 2; y < scene->camera.height; y += 5)
    for (int x = 1; x < scene->camera.width; x += 7) {
      const Ray ray = camera.ray(x + 0.5, y + 0.5);
      if (const auto hit = tracer.intersect(ray.origin, ray.direction)) {
        points.push_back(surface_point(*scene, hit->object, hit->triangle, hit->b1, hit->b2));
        towards_viewer.push_back(-ray.direction);
      }
    }
  ASSERT_GE(points.size(), 20u);
  for (size_t group : {size_t(1), size_t(3), size_t(8)}) {
    for (size_t first = 0; first + group <= points.size(); first += group) {
      std::vector<Sampler> alone, together;
      for (size_t k = 0; k < group; ++k) {
        alone.emplace_back(SamplingMode::sobol, 3, kDomainPixel, first + k, uint32_t(k));
        together.emplace_back(SamplingMode::sobol, 3, kDomainPixel, first + k, uint32_t(k));
      }
      std::vector<Shader::PointToShade> inputs;
      for (size_t k = 0; k < group; ++k)
        inputs.push_back({&points[first + k], towards_viewer[first + k], &together[k]});
      std::vector<glm::dvec3> shaded(group);
      RayCounts counts_together, counts_alone;
      shader.radiance_many(inputs, counts_together, shaded.data());
      for (size_t k = 0; k < group; ++k) {
        const glm::dvec3 own = shader.radiance(points[first + k], towards_viewer[first + k], true,
                                               alone[k], counts_alone);
        for (int c = 0; c < 3; ++c) EXPECT_EQ(shaded[k][c], own[c]) << group << " " << first + k;
      }
      EXPECT_EQ(counts_together.shadow, counts_alone.shadow) << "every shadow ray counted once";
    }
  }
}

}  // namespace
}  // namespace countershade
