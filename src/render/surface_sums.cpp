#include "render/surface_sums.h"

#include "render/render_types.h"

namespace countershade {

SurfaceSums::SurfaceSums(size_t pixels) {
  for (int r = 0; r < 2; ++r) {
    first_[r].assign(pixels, Group{});
    has_more_[r].assign(pixels, 0);
  }
}

void SurfaceSums::add_to(Groups& groups, uint32_t surface, uint32_t count,
                         const glm::dvec3& radiance) {
  for (Group& g : groups)
    if (g.surface == surface) {
      g.count += count;
      g.radiance += radiance;
      return;
    }
  groups.push_back({surface, count, radiance});
}

void SurfaceSums::add(int replicate, size_t pixel, uint32_t surface, const glm::dvec3& radiance) {
  Group& first = first_[replicate][pixel];
  if (first.count == 0 || first.surface == surface) {
    first.surface = surface;
    ++first.count;
    first.radiance += radiance;
    return;
  }
  has_more_[replicate][pixel] = 1;
  Shard& s = shard(pixel);
  std::lock_guard<std::mutex> lock(s.mutex);
  add_to(s.more[2 * pixel + size_t(replicate)], surface, 1, radiance);
}

// The groups of one replicate appended to `out`, merged with what it holds by surface.
void SurfaceSums::groups_of(int replicate, size_t pixel, Groups& out) const {
  const Group& first = first_[replicate][pixel];
  if (first.count == 0) return;
  add_to(out, first.surface, first.count, first.radiance);
  if (!has_more_[replicate][pixel]) return;
  const Shard& s = shard(pixel);
  std::lock_guard<std::mutex> lock(s.mutex);
  for (const Group& g : s.more.at(2 * pixel + size_t(replicate)))
    add_to(out, g.surface, g.count, g.radiance);
}

void SurfaceSums::add_luminance(const Group& g, const Exposure& exposure, Luminance& out) {
  if (g.count == 0) return;
  const double weighted = g.count * display_luminance(g.radiance / double(g.count), exposure);
  (g.surface == kBackground ? out.background : out.surfaces) += weighted;
}

SurfaceSums::Luminance SurfaceSums::weighted_luminance(int replicate, size_t pixel,
                                                       const Exposure& exposure) const {
  Luminance out;
  // Most pixels see one surface in a replicate, the same in both: nothing to merge.
  if (replicate >= 0 && !has_more_[replicate][pixel]) {
    add_luminance(first_[replicate][pixel], exposure, out);
    return out;
  }
  const Group &a = first_[0][pixel], &b = first_[1][pixel];
  if (replicate < 0 && !has_more_[0][pixel] && !has_more_[1][pixel] &&
      (b.count == 0 || a.surface == b.surface)) {
    add_luminance({a.surface, a.count + b.count, a.radiance + b.radiance}, exposure, out);
    return out;
  }
  thread_local Groups groups;
  groups.clear();
  for (int r = 0; r < 2; ++r)
    if (replicate < 0 || r == replicate) groups_of(r, pixel, groups);
  for (const Group& g : groups) add_luminance(g, exposure, out);
  return out;
}

}  // namespace countershade
