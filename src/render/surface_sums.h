#pragma once
// The radiance a pixel's samples bring back from each surface, kept apart per surface and per
// replicate, so that a surface's display luminance is taken of its mean radiance: the display's
// clamp at white applies to the averaged value, as it does to the whole pixel, never to single
// samples (docs/methods.md, "3D unsharp masking", the contrast). A surface is one side of one
// object; the background (samples that hit nothing) is kept as one more. Most pixels see one
// surface; the few that see more keep the others in a shared table.
//
// Threads: add() for a pixel is called by the one thread that samples it at that moment; the
// reads (display_luminance) come after the sampling round, when nothing adds.

#include <array>
#include <cstdint>
#include <glm/vec3.hpp>
#include <mutex>
#include <unordered_map>
#include <vector>

#include "core/display.h"

namespace countershade {

class SurfaceSums {
 public:
  explicit SurfaceSums(size_t pixels);

  static constexpr uint32_t kBackground = 0xffffffffu;
  static uint32_t surface_of(unsigned object, bool back) {
    return 2 * uint32_t(object) + uint32_t(back);
  }

  // One sample of `pixel` in replicate `replicate` that brought `radiance` back from `surface`
  // (surface_of, or kBackground).
  void add(int replicate, size_t pixel, uint32_t surface, const glm::dvec3& radiance);

  // Σ over a pixel's surfaces of (samples on it) · (display luminance of its mean radiance): over
  // the surfaces, and over the background apart. For one replicate, or for both (replicate −1,
  // each surface's samples of the two pooled).
  struct Luminance {
    double surfaces = 0, background = 0;
  };
  Luminance weighted_luminance(int replicate, size_t pixel, const Exposure& exposure) const;

 private:
  struct Group {
    uint32_t surface = 0;
    uint32_t count = 0;  // 0: unused
    glm::dvec3 radiance{0.0};
  };
  using Groups = std::vector<Group>;
  static void add_luminance(const Group& g, const Exposure& exposure, Luminance& out);
  static void add_to(Groups& groups, uint32_t surface, uint32_t count, const glm::dvec3& radiance);
  void groups_of(int replicate, size_t pixel, Groups& out) const;

  struct Shard {
    mutable std::mutex mutex;
    std::unordered_map<size_t, Groups>
        more;  // key 2·pixel + replicate: the surfaces after the first
  };
  static constexpr size_t kShards = 64;
  Shard& shard(size_t pixel) const { return shards_[pixel % kShards]; }

  std::vector<Group> first_[2];       // [replicate][pixel]: the first surface a pixel's samples hit
  std::vector<uint8_t> has_more_[2];  // [replicate][pixel]: some sample hit another surface
  mutable std::array<Shard, kShards> shards_;
};

}  // namespace countershade
