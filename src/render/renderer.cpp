#include "render/renderer.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>
#include <mutex>
#include <optional>

#include "core/color.h"
#include "core/parallel.h"
#include "render/camera.h"
#include "render/camera_samples.h"
#include "render/pixel_pass.h"
#include "render/record_replay.h"
#include "render/shading.h"
#include "render/trace_log.h"
#include "render/vertex_pass.h"

namespace countershade {
namespace {

// What pixel p's centre ray (along `direction`) sees, into the G-buffer.
void store_centre(const Scene& scene, const CameraRays& camera, const Hit& hit,
                  const glm::dvec3& direction, size_t p, GBuffer& g) {
  const SurfacePoint sp = surface_point(scene, hit.object, hit.triangle, hit.b1, hit.b2);
  const bool back = glm::dot(sp.geometric_normal, -direction) < 0;
  g.depth[p] = float(camera.eye_depth(sp.position));
  g.normal[p] = glm::vec3(back ? -sp.shading_normal : sp.shading_normal);
  g.object[p] = int32_t(hit.object);
  g.triangle[p] = int32_t(hit.triangle);
  g.barycentrics[p] = glm::vec2(float(hit.b1), float(hit.b2));
  g.back[p] = back;
}

// Pass 1: the G-buffer from the ray through each pixel centre.
GBuffer centre_pass(const Scene& scene, const RayTracer& tracer, int threads, RayCounts& rays) {
  const int width = scene.camera.width, height = scene.camera.height;
  const size_t n = size_t(width) * height;
  GBuffer g;
  g.width = width;
  g.height = height;
  g.depth.assign(n, std::numeric_limits<float>::infinity());
  g.normal.assign(n, glm::vec3(0.0f));
  g.object.assign(n, -1);
  g.triangle.assign(n, -1);
  g.barycentrics.assign(n, glm::vec2(0.0f));
  g.back.assign(n, 0);
  const CameraRays camera(scene.camera);
  parallel_ranges(
      n, threads,
      [&](size_t begin, size_t end) {
        // Neighbouring pixels' centres a packet at a time: their rays nearly coincide.
        for (size_t first = begin; first < end; first += RayTracer::kPacket) {
          const int count = int(std::min<size_t>(RayTracer::kPacket, end - first));
          glm::dvec3 origins[RayTracer::kPacket] = {}, directions[RayTracer::kPacket] = {};
          std::optional<Hit> hits[RayTracer::kPacket];
          for (int k = 0; k < count; ++k) {
            const size_t p = first + size_t(k);
            const Ray centre =
                camera.ray(double(p % size_t(width)) + 0.5, double(p / size_t(width)) + 0.5);
            origins[k] = centre.origin;
            directions[k] = centre.direction;
          }
          tracer.intersect_packet(count, origins, directions, hits);
          for (int k = 0; k < count; ++k)
            if (hits[k]) store_centre(scene, camera, *hits[k], directions[k], first + size_t(k), g);
        }
      },
      1024);
  rays.primary += n;
  return g;
}

// Objects whose back the camera sees at some pixel centre.
std::vector<bool> seen_from_behind(const GBuffer& g, size_t objects) {
  std::vector<bool> back(objects, false);
  for (size_t p = 0; p < g.object.size(); ++p)
    if (g.object[p] >= 0 && g.back[p]) back[size_t(g.object[p])] = true;
  return back;
}

// The log to replay, if it is one of this camera's size and was kept whole.
const TraceLog* replayable(const TraceLog* log, const Scene& scene) {
  if (!log || log->abandoned()) return nullptr;
  return log->pixel_count() == size_t(scene.camera.width) * size_t(scene.camera.height) ? log
                                                                                        : nullptr;
}

// A render that keeps its radiance only, when the replayed log's records give it alone.
std::optional<RenderResult> from_records_alone(const Scene& scene, const Shader& shader,
                                               const TraceLog* replay,
                                               const RenderOptions& options) {
  if (!replay || !options.radiance_only || options.vertex_radiance || options.record_trace)
    return std::nullopt;
  auto radiance = replay_radiance(scene, shader, *replay, options.threads);
  if (!radiance) return std::nullopt;
  const uint32_t spp = uint32_t(*scene.settings.spp);
  RenderResult result;
  result.radiance = std::move(*radiance);
  result.spp.assign(result.radiance.pixels.size() / 3, spp);
  result.sampling.pixels = {spp, spp, double(spp)};
  return result;
}

}  // namespace

GBuffer render_gbuffer(const Scene& scene, const RayTracer& tracer, int threads) {
  RayCounts rays;
  return centre_pass(scene, tracer, threads, rays);
}

RenderResult render(const Scene& scene, const RayTracer& tracer, const RenderOptions& options) {
  const Shader shader(scene, tracer, options.shading_hook.get(), options.texture_hook.get());
  RenderResult result;
  const TraceLog* replay = replayable(options.replay_trace.get(), scene);
  if (auto replayed = from_records_alone(scene, shader, replay, options))
    return std::move(*replayed);
  result.gbuffer =
      replay ? replay->gbuffer : centre_pass(scene, tracer, options.threads, result.rays);
  // With a fixed count the camera samples are known before the pixels, and a pixel's samples are
  // traced side by side as packets (cheaper than one by one, bunny-sky, docs/performance.md). A
  // vertex pass needs them first: their hits tell it exactly which triangles the pixels read, and
  // the pixel pass reads them back. Without one, the pixel pass traces its packets itself.
  std::shared_ptr<const CameraHits> camera_hits;
  if (!replay && options.trace_ahead && options.vertex_radiance)
    camera_hits = trace_camera_samples(scene, tracer, options.threads);
  if (options.vertex_radiance) {
    std::vector<VertexNeed> needs = options.vertex_needs;
    needs.resize(scene.objects.size(), VertexNeed{scene.settings.noise.target, 1});
    VertexPassInput in{scene,
                       tracer,
                       shader,
                       result.gbuffer,
                       options.ring_samples,
                       seen_from_behind(result.gbuffer, scene.objects.size()),
                       std::move(needs),
                       options.threads,
                       camera_hits.get()};
    result.vertices = vertex_pass(in, &result.rays);
  }
  PixelRequest request;
  if (options.before_pixels) request = options.before_pixels(result);
  std::shared_ptr<TraceLog> record;
  if (options.record_trace)
    record = std::make_shared<TraceLog>(result.gbuffer.depth.size(), options.trace_byte_limit,
                                        shader.light_samples());
  pixel_pass({scene, tracer, shader, request, options.threads, options.progress, record.get(),
              replay, options.estimate_noise, camera_hits.get(), options.trace_ahead},
             result);
  if (record && !record->abandoned()) {
    record->gbuffer = result.gbuffer;
    result.trace = std::move(record);
  }
  return result;
}

}  // namespace countershade
