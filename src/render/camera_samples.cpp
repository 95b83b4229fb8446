#include "render/camera_samples.h"

#include <algorithm>
#include <atomic>

#include "core/parallel.h"
#include "core/random.h"
#include "render/camera.h"

namespace countershade {

constexpr uint64_t kMaxHitBytes = uint64_t(128) << 20;
constexpr int kTile = 16;

std::vector<uint32_t> tile_order(int width, int height) {
  std::vector<uint32_t> order;
  order.reserve(size_t(width) * height);
  for (int ty = 0; ty < height; ty += kTile)
    for (int tx = 0; tx < width; tx += kTile)
      for (int y = ty; y < std::min(ty + kTile, height); ++y)
        for (int x = tx; x < std::min(tx + kTile, width); ++x)
          order.push_back(uint32_t(y * width + x));
  return order;
}

void latin_hypercube(uint64_t seed, uint64_t pixel, int spp, std::vector<glm::dvec2>& out) {
  out.resize(size_t(spp));
  SampleStream random(seed, kDomainCamera, pixel, 0);
  std::vector<int> permutation(static_cast<size_t>(spp));
  for (int i = 0; i < spp; ++i) permutation[size_t(i)] = i;
  for (int i = spp - 1; i > 0; --i)
    std::swap(permutation[size_t(i)],
              permutation[size_t(std::min(i, int(random.next() * (i + 1))))]);
  for (int i = 0; i < spp; ++i)
    out[size_t(i)] = {(i + random.next()) / spp, (permutation[size_t(i)] + random.next()) / spp};
}

glm::dvec2 sample_position(const RenderSettings& settings, Sampler& sampler,
                           const std::vector<glm::dvec2>& lhs, uint32_t s) {
  if (settings.sampling == SamplingMode::independent) return lhs[s];
  if (settings.spp.value_or(0) == 1) return glm::dvec2(0.5);
  return sampler.next2d();
}

CameraHits::CameraHits(size_t pixels, uint32_t spp, const Scene& scene)
    : spp_(spp),
      samples_(std::make_unique_for_overwrite<PackedHit[]>(pixels * spp)),
      count_(pixels * spp),
      seen_(scene.objects.size()) {
  for (size_t o = 0; o < seen_.size(); ++o)
    seen_[o].assign(scene.objects[o].mesh.triangle_count(), 0);
}

std::shared_ptr<const CameraHits> trace_camera_samples(const Scene& scene, const RayTracer& tracer,
                                                       int threads) {
  const RenderSettings& settings = scene.settings;
  const int width = scene.camera.width;
  const size_t pixels = size_t(width) * size_t(scene.camera.height);
  if (!settings.spp || pixels * uint64_t(*settings.spp) * sizeof(PackedHit) > kMaxHitBytes)
    return nullptr;
  const uint32_t spp = uint32_t(*settings.spp);
  auto hits = std::make_shared<CameraHits>(pixels, spp, scene);
  const CameraRays rays(scene.camera);
  const std::vector<uint32_t> order =
      tile_order(width, scene.camera.height);  // the pixel pass's order
  parallel_ranges(
      order.size(), threads,
      [&](size_t begin, size_t end) {
        std::vector<glm::dvec2> lhs;
        for (size_t i = begin; i < end; ++i) {
          const size_t pixel = order[i];
          if (settings.sampling == SamplingMode::independent)
            latin_hypercube(settings.seed, pixel, int(spp), lhs);
          // A pixel's samples, a packet at a time: their rays nearly coincide, so they share the
          // traversal (twice as fast as one by one on bunny-sky, docs/performance.md).
          for (uint32_t first = 0; first < spp; first += RayTracer::kPacket) {
            const int count = int(std::min<uint32_t>(RayTracer::kPacket, spp - first));
            glm::dvec3 origins[RayTracer::kPacket], directions[RayTracer::kPacket];
            std::optional<Hit> traced[RayTracer::kPacket];
            for (int k = 0; k < count; ++k) {
              Sampler sampler(settings.sampling, settings.seed, kDomainPixel, pixel,
                              first + uint32_t(k));
              const glm::dvec2 offset =
                  sample_position(settings, sampler, lhs, first + uint32_t(k));
              const Ray ray = rays.ray(int(pixel % size_t(width)) + offset.x,
                                       int(pixel / size_t(width)) + offset.y);
              origins[k] = ray.origin;
              directions[k] = ray.direction;
            }
            tracer.intersect_packet(count, origins, directions, traced);
            for (int k = 0; k < count; ++k) {
              const PackedHit packed = PackedHit::of(traced[k]);
              hits->samples_[pixel * spp + first + uint32_t(k)] = packed;
              // Every writer stores the same 1: relaxed stores keep the marks race-free.
              if (packed.object >= 0)
                std::atomic_ref<uint8_t>(hits->seen_[size_t(packed.object)][packed.triangle])
                    .store(1, std::memory_order_relaxed);
            }
          }
        }
      },
      64);
  return hits;
}

}  // namespace countershade
