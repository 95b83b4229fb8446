#pragma once
// Where a render's camera samples fall, and, for a render with a fixed count, every camera
// sample's hit traced ahead of the pixel pass.
//
// Traced a pixel's samples at a time, as ray packets, they cost less than the pixel pass tracing
// them one by one; the pixel pass then reads its camera rays' hits from them (the same rays give
// the same hits). They also tell the vertex pass exactly which triangles some pixel reads, so that
// it shades no vertex that only the view's frustum, not a camera ray, reaches (the back of a mesh,
// the ground hidden behind it).

#include <cstdint>
#include <glm/vec2.hpp>
#include <memory>
#include <optional>
#include <vector>

#include "core/sampler.h"
#include "render/ray_tracer.h"
#include "render/scene.h"

namespace countershade {

// Pixel indices tile by tile (16×16), so that neighbouring samples share caches.
std::vector<uint32_t> tile_order(int width, int height);

// Latin-hypercube positions for `spp` samples in the unit pixel (the independent sampler's).
void latin_hypercube(uint64_t seed, uint64_t pixel, int spp, std::vector<glm::dvec2>& out);

// The position of sample `s` within its pixel, in [0, 1)²: the pixel's Latin hypercube with the
// independent sampler (`lhs`, from latin_hypercube), else the sampler's first two dimensions (the
// centre when a fixed count takes one sample).
glm::dvec2 sample_position(const RenderSettings& settings, Sampler& sampler,
                           const std::vector<glm::dvec2>& lhs, uint32_t s);

class CameraHits {
 public:
  CameraHits(size_t pixels, uint32_t spp, const Scene& scene);

  uint32_t spp() const { return spp_; }
  std::optional<Hit> hit(size_t pixel, uint32_t s) const {
    return samples_[pixel * spp_ + s].unpack();
  }
  // Per triangle of an object: whether some camera sample hits it (from either side).
  const std::vector<uint8_t>& triangles_hit(unsigned object) const { return seen_[object]; }

 private:
  friend std::shared_ptr<const CameraHits> trace_camera_samples(const Scene&, const RayTracer&,
                                                                int);
  uint32_t spp_;
  std::unique_ptr<PackedHit[]>
      samples_;  // pixel-major, left uninitialised: the tracing writes each
  size_t count_;
  std::vector<std::vector<uint8_t>> seen_;  // [object][triangle]
};

// Every camera sample of a render with a fixed count, traced; none without a fixed count, or when
// the hits would take more than 128 MB (16 bytes a sample: 1024×768 at 10 samples per pixel).
std::shared_ptr<const CameraHits> trace_camera_samples(const Scene& scene, const RayTracer& tracer,
                                                       int threads);

}  // namespace countershade
