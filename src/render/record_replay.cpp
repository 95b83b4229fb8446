#include "render/record_replay.h"

#include <algorithm>
#include <glm/geometric.hpp>
#include <vector>

#include "core/parallel.h"
#include "core/sampler.h"

namespace countershade {

ReplayedSample replay_sample(const Scene& scene, const Shader& shader, const TraceLog& log,
                             size_t pixel, uint32_t sample) {
  ReplayedSample out;
  const auto hit = log.hit(pixel, sample);
  if (!hit) {
    out.radiance = log.background(pixel, sample);
    return out;
  }
  const ShadingRecord& record = log.shading(pixel, sample);
  out.point = record.restore(surface_point(scene, hit->object, hit->triangle, hit->b1, hit->b2));
  // The camera ray's direction is −wo, so the side it saw is that of dot(n_g, −wo).
  out.back = glm::dot(out.point->geometric_normal, -record.wo) > 0;
  out.radiance = shader.replay(*out.point, record, log.light_samples(pixel, sample));
  return out;
}

namespace {

bool holds_every_record(const TraceLog& log, uint32_t samples) {
  if (log.abandoned() || !log.keeps_shading()) return false;
  for (size_t p = 0; p < log.pixel_count(); ++p)
    if (!log.has_shading(p, samples - 1) || log.has(p, samples)) return false;
  return true;
}

// Pixels replayed together, so that the shading hook sees all their samples in one call.
constexpr size_t kReplayPixels = 16;

// The radiance of pixels [first, end) into `radiance`: each sample is its background or its record
// evaluated again, summed per replicate in sample order (as the pixel pass sums them).
void replay_pixels(const Scene& scene, const Shader& shader, const TraceLog& log, uint32_t samples,
                   size_t first, size_t end, Image& radiance) {
  thread_local std::vector<SurfacePoint> points;
  thread_local std::vector<ReplayInput> inputs;
  thread_local std::vector<size_t> slots;  // each input's place in `values`
  thread_local std::vector<glm::dvec3> values, replayed;
  const size_t count = (end - first) * samples;
  points.clear();
  points.reserve(count);  // `inputs` points into it: no reallocation below
  inputs.clear();
  slots.clear();
  values.resize(count);
  for (size_t p = first, slot = 0; p < end; ++p)
    for (uint32_t s = 0; s < samples; ++s, ++slot) {
      const auto hit = log.hit(p, s);
      if (!hit) {
        values[slot] = log.background(p, s);
        continue;
      }
      const ShadingRecord& record = log.shading(p, s);
      points.push_back(
          record.restore(surface_point(scene, hit->object, hit->triangle, hit->b1, hit->b2)));
      inputs.push_back({&points.back(), &record, log.light_samples(p, s)});
      slots.push_back(slot);
    }
  replayed.resize(inputs.size());
  shader.replay_many(inputs, replayed.data());
  for (size_t j = 0; j < inputs.size(); ++j) values[slots[j]] = replayed[j];
  for (size_t p = first, slot = 0; p < end; ++p) {
    glm::dvec3 sums[2] = {glm::dvec3(0.0), glm::dvec3(0.0)};
    for (uint32_t s = 0; s < samples; ++s, ++slot) sums[Sampler::replicate(s)] += values[slot];
    for (int c = 0; c < 3; ++c)
      radiance.pixels[3 * p + size_t(c)] = float((sums[0][c] + sums[1][c]) / double(samples));
  }
}

}  // namespace

std::optional<Image> replay_radiance(const Scene& scene, const Shader& shader, const TraceLog& log,
                                     int threads) {
  const int width = scene.camera.width, height = scene.camera.height;
  const std::optional<int> spp = scene.settings.spp;
  if (!spp || *spp < 1 || log.pixel_count() != size_t(width) * size_t(height)) return std::nullopt;
  const uint32_t samples = uint32_t(*spp);
  if (!holds_every_record(log, samples)) return std::nullopt;
  Image radiance(width, height, 3, Image::Uninitialized{});
  parallel_ranges(
      log.pixel_count(), threads,
      [&](size_t begin, size_t end) {
        for (size_t first = begin; first < end; first += kReplayPixels)
          replay_pixels(scene, shader, log, samples, first, std::min(end, first + kReplayPixels),
                        radiance);
      },
      256);
  return radiance;
}

}  // namespace countershade
