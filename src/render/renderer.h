#pragma once
// One render of a view: the linear radiance image, a G-buffer from the pixel-centre rays and,
// on request, the outgoing radiance towards the camera at every mesh vertex.

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/image.h"
#include "render/hooks.h"
#include "render/ray_tracer.h"
#include "render/scene.h"

namespace countershade {

struct RenderOptions {
  int threads = 0;               // 0 = all cores
  bool vertex_radiance = false;  // also shade every mesh vertex
  int ring_samples = 0;          // per-vertex anti-aliasing: samples per incident triangle
  std::shared_ptr<const ShadingHook> shading_hook;  // optional (render/hooks.h)
  std::shared_ptr<const TextureHook> texture_hook;
  std::function<void(double)> progress;  // called with the finished fraction, from any thread
};

// Per-pixel data from the ray through each pixel centre. Background pixels have object = -1,
// depth = +inf and a zero normal.
struct GBuffer {
  int width = 0, height = 0;
  std::vector<float> depth;                // linear eye depth
  std::vector<glm::vec3> normal;           // world-space shading normal, facing the camera
  std::vector<int32_t> object, triangle;   // ids, -1 for background
  std::vector<glm::vec2> barycentrics;     // (b1, b2) of the hit triangle
  size_t index(int x, int y) const { return size_t(y) * width + x; }
};

struct RenderResult {
  Image radiance;  // linear RGB
  GBuffer gbuffer;
  std::vector<std::vector<glm::vec3>> vertex_radiance;  // [object][vertex], when requested
  RayCounts rays;
};

RenderResult render(const Scene& scene, const RayTracer& tracer, const RenderOptions& options = {});

// Outgoing radiance towards the camera at every vertex of every object. A vertex whose incident
// corners differ (a crease or a UV seam) gets the mean over those corners, weighted by how many
// corners share each variant, shaded with the scene's vertex_samples(). With `ring_samples` =
// k > 0, every triangle is shaded at k fixed barycentric points (one sample each) and a vertex
// averages its own value with the points of all its incident triangles: anti-aliasing over the
// 1-ring. The vertex itself then takes one sample (the ring points do the averaging). The
// offsets are the same every frame, so the signal stays temporally coherent.
std::vector<std::vector<glm::vec3>> render_vertex_radiance(const Scene& scene, const RayTracer& tracer,
                                                           const RenderOptions& options, RayCounts* counts = nullptr);

// The fixed barycentric coordinates (b0, b1, b2) of sample j of k on every triangle: stratified
// over the triangle's area.
glm::dvec3 triangle_sample_barycentrics(int j, int k);

}  // namespace countershade
