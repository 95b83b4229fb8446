#include "render/vertex_pass.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <mutex>
#include <tuple>
#include <utility>

#include "core/color.h"
#include "core/parallel.h"
#include "core/random.h"
#include "render/camera.h"

namespace countershade {
namespace {

constexpr uint64_t kBackDomain = 16;  // added to a domain for the back side

// Replicate sums of radiance at one shading point, and how many samples each holds.
struct PointSums {
  glm::dvec3 sum[2] = {glm::dvec3(0.0), glm::dvec3(0.0)};
  uint32_t n[2] = {0, 0};
  bool has(int r) const { return r < 0 ? n[0] + n[1] > 0 : n[r] > 0; }
  // The mean of replicate r, or of every sample with r = -1.
  glm::dvec3 mean(int r) const {
    if (r < 0) return has(r) ? (sum[0] + sum[1]) / double(n[0] + n[1]) : glm::dvec3(0.0);
    return n[r] ? sum[r] / double(n[r]) : glm::dvec3(0.0);
  }
};

// The distinct shading variants of each needed vertex (none for the rest): a representative
// corner and how many corners share its normal and UV.
struct Variants {
  std::vector<uint32_t> offsets;                       // #V + 1
  std::vector<std::pair<uint32_t, uint32_t>> entries;  // (corner, count)
};

Variants vertex_variants(const TriangleMesh& mesh, const VertexCorners& vc,
                         const std::vector<uint8_t>& needed, int threads) {
  // Each vertex's variants go first into its own corners' slots (at most one per corner), in
  // parallel, then are packed.
  struct Entry {
    uint32_t corner, count;
  };
  const size_t nv = mesh.vertex_count();
  const auto slots =
      std::make_unique_for_overwrite<Entry[]>(vc.corners.size());  // only needed ones are touched
  std::vector<uint32_t> count(nv, 0);
  parallel_ranges(
      nv, threads,
      [&](size_t begin, size_t end) {
        for (size_t v = begin; v < end; ++v) {
          if (!needed[v]) continue;
          Entry* first = slots.get() + vc.offsets[v];
          for (uint32_t i = vc.offsets[v]; i < vc.offsets[v + 1]; ++i) {
            const uint32_t corner = vc.corners[i];
            auto same = [&](const Entry& e) {
              return mesh.corner_normals[e.corner] == mesh.corner_normals[corner] &&
                     (!mesh.has_uvs() || mesh.corner_uvs[e.corner] == mesh.corner_uvs[corner]);
            };
            Entry* it = std::find_if(first, first + count[v], same);
            if (it != first + count[v])
              ++it->count;
            else
              first[count[v]++] = {corner, 1};
          }
        }
      },
      1024);
  Variants out;
  out.offsets.assign(nv + 1, 0);
  for (size_t v = 0; v < nv; ++v) out.offsets[v + 1] = out.offsets[v] + count[v];
  out.entries.resize(out.offsets[nv]);
  parallel_ranges(
      nv, threads,
      [&](size_t begin, size_t end) {
        for (size_t v = begin; v < end; ++v)
          for (uint32_t i = 0; i < count[v]; ++i) {
            const Entry& e = slots[vc.offsets[v] + i];
            out.entries[out.offsets[v] + i] = {e.corner, e.count};
          }
      },
      1024);
  return out;
}

constexpr uint32_t kNoSlot = UINT32_MAX;

// Where each triangle's ring points are kept: only the triangles with a needed corner have them
// (on a large ground plane most are out of view). Returns the slots and their count.
std::pair<std::vector<uint32_t>, size_t> ring_slots(const TriangleMesh& mesh,
                                                    const std::vector<uint8_t>& needed) {
  std::vector<uint32_t> slot(mesh.triangle_count(), kNoSlot);
  uint32_t count = 0;
  for (size_t t = 0; t < slot.size(); ++t) {
    const glm::uvec3& c = mesh.triangles[t];
    if (needed[c.x] || needed[c.y] || needed[c.z]) slot[t] = count++;
  }
  return {std::move(slot), count};
}

// One object, one side: its points, their sums, and the rounds.
class ObjectSide {
 public:
  ObjectSide(const VertexPassInput& in, unsigned object, bool back, uint64_t vertex_offset,
             uint64_t triangle_offset, const std::vector<uint8_t>& needed)
      : in_(in),
        object_(object),
        back_(back),
        needed_(needed),
        mesh_(in.scene.objects[object].mesh),
        corners_(vertex_corners(mesh_)),
        variants_(vertex_variants(mesh_, corners_, needed, in.threads)),
        own_(variants_.entries.size()),
        k_(std::max(in.ring_samples, 0)),
        rays_(in.scene.camera),
        vertex_count_(mesh_.vertex_count(), 0),
        triangle_count_(mesh_.triangle_count(), 0),
        vertex_offset_(vertex_offset),
        triangle_offset_(triangle_offset) {
    if (k_ == 0) return;
    size_t slots = 0;
    std::tie(ring_slot_, slots) = ring_slots(mesh_, needed);
    ring_.resize(slots * size_t(k_));
  }

  // Samples every point of a needed vertex, and of a triangle with a needed corner, up to the
  // counts its vertex (or triangle) asks for.
  void sample(const std::vector<uint32_t>& vertex_target,
              const std::vector<uint32_t>& triangle_target, RayCounts& rays) {
    parallel_ranges(
        mesh_.vertex_count(), in_.threads,
        [&](size_t begin, size_t end) {
          RayCounts counts;
          for (size_t v = begin; v < end; ++v)
            if (needed_[v]) sample_vertex(v, vertex_target[v], counts);
          add(rays, counts);
        },
        256);
    if (ring_.empty()) return;
    parallel_ranges(
        mesh_.triangle_count(), in_.threads,
        [&](size_t begin, size_t end) {
          RayCounts counts;
          for (size_t t = begin; t < end; ++t)
            if (ring_slot_[t] != kNoSlot) sample_triangle(t, triangle_target[t], counts);
          add(rays, counts);
        },
        256);
  }

  bool needed(size_t v) const { return needed_[v]; }

  // The vertex's value from replicate r (or from all samples with r = -1): the mean over its own
  // point and its ring points, of those that hold samples of r.
  glm::dvec3 value(size_t v, int r) const {
    glm::dvec3 own(0.0);
    double weight = 0;
    const bool has_own =
        variants_.offsets[v] < variants_.offsets[v + 1] && own_[variants_.offsets[v]].has(r);
    for (uint32_t i = variants_.offsets[v]; i < variants_.offsets[v + 1]; ++i) {
      const double count = variants_.entries[i].second;
      own += count * own_[i].mean(r);
      weight += count;
    }
    own = weight > 0 ? own / weight : own;
    if (k_ == 0) return own;
    glm::dvec3 ring(0.0);
    double points = 0;
    for (uint32_t i = corners_.offsets[v]; i < corners_.offsets[v + 1]; ++i) {
      const uint32_t slot =
          ring_slot_[corners_.corners[i] / 3];  // every triangle of a needed vertex has one
      for (int j = 0; j < k_; ++j)
        if (ring_[size_t(slot) * k_ + j].has(r)) {
          ring += ring_[size_t(slot) * k_ + j].mean(r);
          points += 1.0;
        }
    }
    const double all = (has_own ? 1.0 : 0.0) + points;
    return all > 0 ? (own + ring) / all : own;
  }

  const std::vector<uint32_t>& vertex_samples() const { return vertex_count_; }
  const TriangleMesh& mesh() const { return mesh_; }
  const VertexCorners& corners() const { return corners_; }

 private:
  static void add(RayCounts& total, const RayCounts& counts) {
    static std::mutex mutex;
    std::lock_guard<std::mutex> lock(mutex);
    total += counts;
  }

  SurfacePoint oriented(SurfacePoint sp) const {
    if (back_) {
      sp.geometric_normal = -sp.geometric_normal;
      sp.shading_normal = -sp.shading_normal;
    }
    return sp;
  }

  // Samples [from, to) of a point's stream. A point of one sample takes it from the first or the
  // second replicate by turns (`turn`, the point's number), so that a vertex's points, one sample
  // each, fill both replicates.
  void shade(const SurfacePoint& sp, uint64_t domain, uint64_t index, uint64_t turn, uint32_t from,
             uint32_t to, PointSums& sums, RayCounts& counts) const {
    const RenderSettings& settings = in_.scene.settings;
    const glm::dvec3 wo = rays_.towards_viewer(sp.position);
    const uint32_t first = to == 1 ? uint32_t(turn % 2) : 0;
    for (uint32_t s = first + from; s < first + to; ++s) {
      Sampler sampler(settings.sampling, settings.seed, domain + (back_ ? kBackDomain : 0), index,
                      s);
      const int r = Sampler::replicate(s);
      sums.sum[r] += in_.shader.radiance(sp, wo, false, sampler, counts);
      ++sums.n[r];
    }
  }

  void sample_vertex(size_t v, uint32_t target, RayCounts& counts) {
    if (target <= vertex_count_[v]) return;
    for (uint32_t i = variants_.offsets[v]; i < variants_.offsets[v + 1]; ++i) {
      const uint32_t corner = variants_.entries[i].first, c = corner % 3;
      SurfacePoint sp =
          surface_point(in_.scene, object_, corner / 3, c == 1 ? 1.0 : 0.0, c == 2 ? 1.0 : 0.0);
      sp.position = mesh_.positions[v];  // exactly the vertex, not a barycentric round-off
      shade(oriented(sp), kDomainVertex, hash_combine(vertex_offset_ + v, i - variants_.offsets[v]),
            vertex_offset_ + v, vertex_count_[v], target, own_[i], counts);
    }
    vertex_count_[v] = target;
  }

  void sample_triangle(size_t t, uint32_t target, RayCounts& counts) {
    if (target <= triangle_count_[t]) return;
    for (int j = 0; j < k_; ++j) {
      const glm::dvec3 b = triangle_sample_barycentrics(j, k_);
      const SurfacePoint sp = surface_point(in_.scene, object_, unsigned(t), b.y, b.z);
      const uint64_t point = (triangle_offset_ + t) * uint64_t(k_) + uint64_t(j);
      shade(oriented(sp), kDomainTriangle, point, point, triangle_count_[t], target,
            ring_[size_t(ring_slot_[t]) * k_ + j], counts);
    }
    triangle_count_[t] = target;
  }

  const VertexPassInput& in_;
  unsigned object_;
  bool back_;
  const std::vector<uint8_t>& needed_;  // per vertex: whether any pixel can depend on its value
  const TriangleMesh& mesh_;
  VertexCorners corners_;
  Variants variants_;
  std::vector<PointSums> own_;
  int k_;                            // ring points per triangle
  std::vector<uint32_t> ring_slot_;  // per triangle (with k > 0)
  std::vector<PointSums> ring_;      // k per slot
  CameraRays rays_;
  std::vector<uint32_t> vertex_count_, triangle_count_;
  uint64_t vertex_offset_, triangle_offset_;
};

// The squared L* error of every vertex, pooled: the larger of its own and its 1-ring's mean.
std::vector<double> pooled_variance(const ObjectSide& side, const SurfaceGraph& surface,
                                    const Exposure& exposure, int threads) {
  const size_t nv = side.mesh().vertex_count();
  std::vector<double> variance(nv, 0.0);
  parallel_ranges(
      nv, threads,
      [&](size_t begin, size_t end) {
        for (size_t v = begin; v < end; ++v) {
          if (!side.needed(v)) continue;  // unshaded (and no refined vertex pools it)
          const double L0 = cielab_lightness(display_luminance(side.value(v, 0), exposure));
          const double L1 = cielab_lightness(display_luminance(side.value(v, 1), exposure));
          variance[v] = 0.25 * (L0 - L1) * (L0 - L1);
        }
      },
      1024);
  const std::vector<double> points = surface.to_points(variance);
  std::vector<double> pooled(points.size(), 0.0);
  parallel_ranges(
      points.size(), threads,
      [&](size_t begin, size_t end) {
        for (size_t p = begin; p < end; ++p) {
          if (!side.needed(surface.first_vertex[p]))
            continue;  // a point's vertices are needed together
          double ring = 0;
          for (uint32_t q : surface.adjacency.of(p)) ring += points[q];
          const size_t n = surface.adjacency.of(p).size();
          pooled[p] = std::max(points[p], n ? ring / double(n) : 0.0);
        }
      },
      4096);
  return surface.to_vertices(pooled);
}

// Per vertex: whether it lies within `rings` (of the welded 1-ring graph) of a vertex of a
// triangle for which `seed` holds.
template <typename Seed>
std::vector<uint8_t> near_triangles(const Object& o, int rings, Seed seed) {
  const SurfaceGraph& surface = o.surface;
  std::vector<uint8_t> near(surface.point_count(), 0);
  std::vector<uint32_t> frontier;
  for (size_t t = 0; t < o.mesh.triangle_count(); ++t) {
    if (!seed(t)) continue;
    const glm::uvec3& c = o.mesh.triangles[t];
    for (uint32_t v : {c.x, c.y, c.z})
      if (!near[surface.point_of[v]]) {
        near[surface.point_of[v]] = 1;
        frontier.push_back(surface.point_of[v]);
      }
  }
  for (int ring = 0; ring < rings && !frontier.empty(); ++ring) {
    std::vector<uint32_t> next;
    for (uint32_t p : frontier)
      for (uint32_t q : surface.adjacency.of(p))
        if (!near[q]) {
          near[q] = 1;
          next.push_back(q);
        }
    frontier.swap(next);
  }
  std::vector<uint8_t> out(o.mesh.vertex_count());
  for (size_t v = 0; v < out.size(); ++v) out[v] = near[surface.point_of[v]];
  return out;
}

// The vertices within `rings` of a triangle that a pixel centre sees from this side.
std::vector<uint8_t> relevant_vertices(const GBuffer& g, unsigned object, bool back,
                                       const Object& o, int rings) {
  std::vector<uint8_t> seen(o.mesh.triangle_count(), 0);
  for (size_t p = 0; p < g.object.size(); ++p)
    if (g.object[p] == int32_t(object) && bool(g.back[p]) == back) seen[size_t(g.triangle[p])] = 1;
  return near_triangles(o, rings, [&](size_t t) { return seen[t] != 0; });
}

// Per triangle of an object: whether a camera sample hits it (when the samples were traced ahead)
// or may hit it (it meets the view's frustum).
std::vector<uint8_t> triangles_in_view(const VertexPassInput& in, unsigned object) {
  if (in.camera_hits) return in.camera_hits->triangles_hit(object);
  const TriangleMesh& mesh = in.scene.objects[object].mesh;
  const CameraRays camera(in.scene.camera);
  std::vector<uint8_t> outside(mesh.vertex_count());  // each vertex once, not once per triangle
  parallel_ranges(
      outside.size(), in.threads,
      [&](size_t begin, size_t end) {
        for (size_t v = begin; v < end; ++v)
          outside[v] = uint8_t(camera.outside(mesh.positions[v]));
      },
      4096);
  std::vector<uint8_t> in_view(mesh.triangle_count());
  parallel_ranges(
      in_view.size(), in.threads,
      [&](size_t begin, size_t end) {
        for (size_t t = begin; t < end; ++t) {
          const glm::uvec3& c = mesh.triangles[t];
          in_view[t] = (outside[c.x] & outside[c.y] & outside[c.z]) == 0;
        }
      },
      4096);
  return in_view;
}

// The vertices whose values can reach a pixel: within the need's support of a triangle in view,
// and one ring further (the error pools over a 1-ring), or as far as the refinement looks when
// there is one (under a budget), so that every vertex the refinement weighs is shaded exactly as
// if all were. Every vertex without a support.
std::vector<uint8_t> needed_vertices(const VertexPassInput& in, unsigned object,
                                     const VertexNeed& need) {
  const Object& o = in.scene.objects[object];
  if (need.support < 0) return std::vector<uint8_t>(o.mesh.vertex_count(), 1);
  const bool refined = !in.scene.settings.fixed_vertex_spp();
  const std::vector<uint8_t> in_view = triangles_in_view(in, object);
  return near_triangles(o, (refined ? std::max(need.support, need.rings) : need.support) + 1,
                        [&](size_t t) { return in_view[t] != 0; });
}

// Samples one side of one object to its need (or its fixed count); returns the values and errors.
void sample_side(const VertexPassInput& in, ObjectSide& side, const std::vector<uint8_t>& relevant,
                 const SurfaceGraph& surface, double target, RayCounts& rays,
                 std::vector<glm::vec3>& values, std::vector<float>& noise) {
  const RenderSettings& settings = in.scene.settings;
  const Exposure exposure = in.scene.display.exposure();
  const std::optional<int> fixed = settings.fixed_vertex_spp();
  const uint32_t max = uint32_t(fixed.value_or(settings.noise.max_spp));
  // At a fixed count c with ring points every point takes c/2 (at least 1): a vertex averages about
  // 6k + 1 of them, so its value still holds several times c samples.
  const uint32_t per_point =
      fixed ? uint32_t(in.ring_samples > 0 ? std::max(1, *fixed / 2) : *fixed) : 2;
  std::vector<uint32_t> vertex_target(side.mesh().vertex_count(), per_point);
  std::vector<uint32_t> triangle_target(side.mesh().triangle_count(), per_point);
  std::vector<double> variance;
  for (bool more = true; more;) {
    side.sample(vertex_target, triangle_target, rays);
    variance = pooled_variance(side, surface, exposure, in.threads);
    more = false;
    if (fixed) break;
    for (size_t v = 0; v < variance.size(); ++v) {
      const uint32_t count = side.vertex_samples()[v];
      if (!relevant[v] || !side.needed(v) || variance[v] <= target * target || count >= max)
        continue;
      vertex_target[v] = std::min(2 * count, max);
      for (uint32_t i = side.corners().offsets[v]; i < side.corners().offsets[v + 1]; ++i) {
        const size_t t = side.corners().corners[i] / 3;
        triangle_target[t] = std::max(triangle_target[t], std::min(2 * count, max));
      }
      more = true;
    }
  }
  values.assign(variance.size(), glm::vec3(0.0f));
  noise.assign(variance.size(), 0.0f);
  parallel_ranges(
      variance.size(), in.threads,
      [&](size_t begin, size_t end) {
        for (size_t v = begin; v < end; ++v) {
          if (!side.needed(v)) continue;  // no pixel depends on it
          values[v] = glm::vec3(side.value(v, -1));
          noise[v] = float(std::sqrt(variance[v]));
        }
      },
      1024);
}

// The least, the most and the sum of the per-vertex sample counts over the needed vertices.
struct CountTally {
  uint32_t min = UINT32_MAX, max = 0;
  double total = 0, points = 0;

  void add(const ObjectSide& side) {
    for (size_t v = 0; v < side.vertex_samples().size(); ++v) {
      if (!side.needed(v)) continue;
      const uint32_t c = side.vertex_samples()[v];
      min = std::min(min, c);
      max = std::max(max, c);
      total += c;
      points += 1;
    }
  }
};

// Both sides of one object (the back where the camera sees it): their values, errors and counts.
void object_signal(const VertexPassInput& in, unsigned o, uint64_t vertex_offset,
                   uint64_t triangle_offset, VertexSignal& signal, RayCounts& counts,
                   CountTally& tally) {
  const Object& object = in.scene.objects[o];
  const VertexNeed need = in.needs.at(o);
  const std::vector<uint8_t> needed = needed_vertices(in, o, need);  // the same for both sides
  for (bool back : {false, true}) {
    if (back && !(o < in.back.size() && in.back[o])) continue;
    ObjectSide side(in, o, back, vertex_offset, triangle_offset, needed);
    const bool refined =
        !in.scene.settings.fixed_vertex_spp();  // only a refinement asks what is relevant
    const std::vector<uint8_t> relevant =
        refined ? relevant_vertices(in.gbuffer, o, back, object, need.rings)
                : std::vector<uint8_t>();
    sample_side(in, side, relevant, object.surface, need.noise, counts,
                back ? signal.back[o] : signal.front[o],
                back ? signal.back_noise[o] : signal.front_noise[o]);
    tally.add(side);
  }
}

}  // namespace

VertexSignal vertex_pass(const VertexPassInput& in, RayCounts* rays) {
  require_surface_graphs(in.scene, "vertex pass");
  const auto start = std::chrono::steady_clock::now();
  VertexSignal signal;
  const size_t objects = in.scene.objects.size();
  signal.front.resize(objects);
  signal.back.resize(objects);
  signal.front_noise.resize(objects);
  signal.back_noise.resize(objects);
  RayCounts counts;
  CountTally tally;
  uint64_t vertex_offset = 0, triangle_offset = 0;
  for (unsigned o = 0; o < objects; ++o) {
    object_signal(in, o, vertex_offset, triangle_offset, signal, counts, tally);
    vertex_offset += in.scene.objects[o].mesh.vertex_count();
    triangle_offset += in.scene.objects[o].mesh.triangle_count();
  }
  if (rays) *rays += counts;
  signal.samples = {tally.points ? tally.min : 0, tally.max,
                    tally.points ? tally.total / tally.points : 0.0};
  signal.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return signal;
}

}  // namespace countershade
