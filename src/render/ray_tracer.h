#pragma once
// Embree 3 BVH over every object's triangles. Geometry id = object index, primitive id =
// triangle index, so hits map straight back to the scene.

#include <cstdint>
#include <glm/vec3.hpp>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "render/ray_recorder.h"
#include "render/scene.h"

namespace countershade {

struct Hit {
  unsigned object = 0, triangle = 0;
  double b1 = 0, b2 = 0;  // barycentrics of corners 1 and 2 (corner 0 has 1 - b1 - b2)
  double t = 0;
};

// A camera ray's hit as a render keeps it for later (16 bytes): the barycentrics in single
// precision, as `intersect` rounds them, so that the unpacked hit is the traced one (but for t,
// which no one reading it back uses). No initialisers: large arrays of them are filled, not reset.
struct PackedHit {
  int32_t object;  // -1: the ray hit nothing
  uint32_t triangle;
  float b1, b2;
  static PackedHit of(const std::optional<Hit>& hit) {
    return hit ? PackedHit{int32_t(hit->object), hit->triangle, float(hit->b1), float(hit->b2)}
               : PackedHit{-1, 0, 0, 0};
  }
  std::optional<Hit> unpack() const {
    if (object < 0) return std::nullopt;
    return Hit{unsigned(object), triangle, b1, b2, 0.0};
  }
};

// Per-thread ray counts, summed by the caller (keeps atomics out of the hot loop).
struct RayCounts {
  uint64_t primary = 0, shadow = 0;
  RayCounts& operator+=(const RayCounts& o) {
    primary += o.primary;
    shadow += o.shadow;
    return *this;
  }
};

// An any-hit query: does anything lie along the ray between tnear and tfar?
struct ShadowRay {
  glm::dvec3 origin, direction;
  double tnear = 0, tfar = 0;
};

class RayTracer {
 public:
  explicit RayTracer(const Scene& scene);
  ~RayTracer();
  RayTracer(const RayTracer&) = delete;
  RayTracer& operator=(const RayTracer&) = delete;

  std::optional<Hit> intersect(const glm::dvec3& origin, const glm::dvec3& direction,
                               double tnear = 0.0, double tfar = 1e30) const;
  // Up to kPacket rays traced together (an Embree packet): hits[i] is what
  // intersect(origins[i], directions[i]) gives, found faster when the rays run side by side (the
  // samples of one pixel).
  static constexpr int kPacket = 8;
  void intersect_packet(int count, const glm::dvec3* origins, const glm::dvec3* directions,
                        std::optional<Hit>* hits) const;
  bool occluded(const glm::dvec3& origin, const glm::dvec3& direction, double tnear,
                double tfar) const;
  // occluded() of many rays, blocked[i] for rays[i], traced as Embree packets of up to 16: the same
  // answers, found faster for the rays of a pixel's shading points than one by one.
  void occluded(std::span<const ShadowRay> rays, uint8_t* blocked) const;

  // A distance scale for ray offsets: a small fraction of the scene diagonal.
  double epsilon() const { return epsilon_; }

  // Every ray traced from now on goes to `recorder` as well (none: recording stops). For
  // measurements only; a render's images do not change.
  void record_rays(RayRecorder* recorder) { recorder_ = recorder; }
  // The rays traced through Embree alone, one at a time, in their order: no refinement of the hit,
  // no shading. Returns how many hit something (so that the work cannot be left out).
  size_t replay(const std::vector<RecordedRay>& rays) const;

 private:
  struct Handles;
  std::unique_ptr<Handles> handles_;
  double epsilon_ = 1e-4;
  RayRecorder* recorder_ = nullptr;
};

}  // namespace countershade
