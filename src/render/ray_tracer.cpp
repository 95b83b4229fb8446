#include "render/ray_tracer.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <glm/geometric.hpp>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace countershade {

// In a named namespace, not an anonymous one: RayTracer::Handles, a class of the header, holds it.
namespace ray_tracer_detail {
// One object's triangles as Embree holds them.
struct Triangles {
  const float* vertices = nullptr;    // x y z per vertex
  const unsigned* indices = nullptr;  // three per triangle
};
}  // namespace ray_tracer_detail

namespace {

using ray_tracer_detail::Triangles;

// Embree calls this from C code, so it records the error instead of throwing through it.
void embree_error(void* user, RTCError code, const char* message) {
  auto* error = static_cast<std::string*>(user);
  if (error->empty())
    *error = "Embree error " + std::to_string(int(code)) + ": " + (message ? message : "unknown");
}

glm::dvec3 vertex(const Triangles& g, unsigned index) {
  const float* v = g.vertices + 3 * size_t(index);
  return {double(v[0]), double(v[1]), double(v[2])};
}

// The hit on the triangle Embree found, computed again in double precision (Möller–Trumbore).
// Embree's kernels for different instruction sets (SSE2, AVX2, AVX-512) round t, u and v
// differently, so without this a stimulus would differ in its last bits from one processor to
// another. A degenerate triangle keeps Embree's values.
void refine(const Triangles& g, const glm::dvec3& origin, const glm::dvec3& direction, Hit& hit) {
  const unsigned* corner = g.indices + 3 * size_t(hit.triangle);
  const glm::dvec3 p0 = vertex(g, corner[0]), e1 = vertex(g, corner[1]) - p0,
                   e2 = vertex(g, corner[2]) - p0;
  const glm::dvec3 p = glm::cross(direction, e2);
  const double det = glm::dot(e1, p);
  if (det == 0.0 || !std::isfinite(det)) return;
  const double inverse = 1.0 / det;
  const glm::dvec3 s = origin - p0, q = glm::cross(s, e1);
  const double b1 = std::clamp(glm::dot(s, p) * inverse, 0.0, 1.0);
  const double b2 = std::clamp(glm::dot(direction, q) * inverse, 0.0, 1.0 - b1);
  // Rounded to single precision, Embree's own: a render's trace log keeps them as floats, so a
  // replayed sample is the traced one.
  hit.b1 = double(float(b1));
  hit.b2 = double(float(b2));
  hit.t = glm::dot(e2, q) * inverse;
}

// A single ray as Embree takes it.
RTCRay embree_ray(const float (&origin)[3], const float (&direction)[3], float tnear, float tfar) {
  RTCRay ray;
  ray.org_x = origin[0];
  ray.org_y = origin[1];
  ray.org_z = origin[2];
  ray.dir_x = direction[0];
  ray.dir_y = direction[1];
  ray.dir_z = direction[2];
  ray.tnear = tnear;
  ray.tfar = tfar;
  ray.mask = 0xFFFFFFFF;
  ray.flags = 0;
  ray.time = 0;
  return ray;
}

// The ray in single precision, as Embree receives it.
RecordedRay single_precision(const glm::dvec3& origin, const glm::dvec3& direction, double tnear,
                             double tfar, bool closest) {
  return {{float(origin.x), float(origin.y), float(origin.z)},
          {float(direction.x), float(direction.y), float(direction.z)},
          float(tnear),
          float(std::min(tfar, double(std::numeric_limits<float>::max()))),
          closest};
}

RecordedRay single_precision(const ShadowRay& ray) {
  return single_precision(ray.origin, ray.direction, ray.tnear, ray.tfar, false);
}

// Lane i of a packet of rays (RTCRay8, RTCRay16).
template <class Packet>
void set_lane(Packet& packet, int i, const RecordedRay& r) {
  packet.org_x[i] = r.origin[0];
  packet.org_y[i] = r.origin[1];
  packet.org_z[i] = r.origin[2];
  packet.dir_x[i] = r.direction[0];
  packet.dir_y[i] = r.direction[1];
  packet.dir_z[i] = r.direction[2];
  packet.tnear[i] = r.tnear;
  packet.tfar[i] = r.tfar;
  packet.mask[i] = 0xFFFFFFFF;
  packet.flags[i] = 0;
  packet.time[i] = 0;
}

}  // namespace

struct RayTracer::Handles {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<ray_tracer_detail::Triangles> objects;  // by geometry id
  std::string error;
  ~Handles() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

RayTracer::RayTracer(const Scene& scene) : handles_(std::make_unique<Handles>()) {
  // No "threads=N" here: Debian's Embree schedules through TBB, and a thread limit would become a
  // process-wide TBB limit that also throttles the renderer's own parallel loops.
  handles_->device = rtcNewDevice(nullptr);
  if (!handles_->device) throw std::runtime_error("cannot create Embree device");
  rtcSetDeviceErrorFunction(handles_->device, embree_error, &handles_->error);
  handles_->scene = rtcNewScene(handles_->device);
  rtcSetSceneBuildQuality(handles_->scene, RTC_BUILD_QUALITY_HIGH);
  // Watertight intersection: rays through shared edges or vertices (e.g. a vertex projected onto
  // a pixel centre) must hit one of the triangles, never slip through.
  rtcSetSceneFlags(handles_->scene, RTC_SCENE_FLAG_ROBUST);

  for (size_t id = 0; id < scene.objects.size(); ++id) {
    const TriangleMesh& mesh = scene.objects[id].mesh;
    RTCGeometry geom = rtcNewGeometry(handles_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), mesh.vertex_count()));
    for (size_t v = 0; v < mesh.vertex_count(); ++v)
      std::memcpy(vertices + 3 * v, &mesh.positions[v], 3 * sizeof(float));
    auto* indices = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(unsigned), mesh.triangle_count()));
    for (size_t t = 0; t < mesh.triangle_count(); ++t)
      std::memcpy(indices + 3 * t, &mesh.triangles[t], 3 * sizeof(unsigned));
    handles_->objects.push_back({vertices, indices});
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(handles_->scene, geom, unsigned(id));
    rtcReleaseGeometry(geom);
  }
  rtcCommitScene(handles_->scene);
  // Embree errors are resource or programming errors, never bad user input: exit status 1.
  if (!handles_->error.empty()) throw std::runtime_error(handles_->error);
  epsilon_ = std::max(1e-6, 1e-5 * double(scene.bounds().diagonal()));
}

RayTracer::~RayTracer() = default;

std::optional<Hit> RayTracer::intersect(const glm::dvec3& origin, const glm::dvec3& direction,
                                        double tnear, double tfar) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  const RecordedRay r = single_precision(origin, direction, tnear, tfar, true);
  if (recorder_) recorder_->add(r);
  alignas(16) RTCRayHit rh;
  rh.ray = embree_ray(r.origin, r.direction, r.tnear, r.tfar);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(handles_->scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  Hit hit{rh.hit.geomID, rh.hit.primID, rh.hit.u, rh.hit.v, rh.ray.tfar};
  refine(handles_->objects[hit.object], origin, direction, hit);
  return hit;
}

void RayTracer::intersect_packet(int count, const glm::dvec3* origins, const glm::dvec3* directions,
                                 std::optional<Hit>* hits) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  alignas(32) RTCRayHit8 rh;
  alignas(32) int valid[kPacket];
  for (int i = 0; i < kPacket; ++i) {
    const bool used = i < count;  // the unused lanes are switched off
    valid[i] = used ? -1 : 0;
    const glm::dvec3 o = used ? origins[i] : glm::dvec3(0.0),
                     d = used ? directions[i] : glm::dvec3(0, 0, 1);
    set_lane(rh.ray, i,
             {{float(o.x), float(o.y), float(o.z)},
              {float(d.x), float(d.y), float(d.z)},
              0.0f,
              std::numeric_limits<float>::max(),
              true});
    rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
  }
  rtcIntersect8(valid, handles_->scene, &context, &rh);
  if (recorder_)
    for (int i = 0; i < count; ++i)
      recorder_->add(single_precision(origins[i], directions[i], 0.0, 1e30, true));
  for (int i = 0; i < count; ++i) {
    if (rh.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) {
      hits[i] = std::nullopt;
      continue;
    }
    Hit hit{rh.hit.geomID[i], rh.hit.primID[i], rh.hit.u[i], rh.hit.v[i], rh.ray.tfar[i]};
    refine(handles_->objects[hit.object], origins[i], directions[i], hit);  // as intersect does
    hits[i] = hit;
  }
}

bool RayTracer::occluded(const glm::dvec3& origin, const glm::dvec3& direction, double tnear,
                         double tfar) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  const RecordedRay r = single_precision(origin, direction, tnear, tfar, false);
  if (recorder_) recorder_->add(r);
  alignas(16) RTCRay ray = embree_ray(r.origin, r.direction, r.tnear, r.tfar);
  rtcOccluded1(handles_->scene, &context, &ray);
  return ray.tfar < 0.0f;
}

namespace {

// Up to N rays as one Embree packet (N = 8 or 16): blocked[i] for rays[i].
template <int N, class Packet>
void occluded_packet(RTCScene scene, RayRecorder* recorder, std::span<const ShadowRay> rays,
                     uint8_t* blocked) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  const int count = int(rays.size());
  alignas(64) Packet packet;
  alignas(64) int valid[N];
  RecordedRay r{};
  for (int i = 0; i < count; ++i) {
    r = single_precision(rays[size_t(i)]);
    if (recorder) recorder->add(r);
    set_lane(packet, i, r);
  }
  // The unused lanes are switched off, with the last ray's values (never NaN) in them.
  for (int i = count; i < N; ++i) set_lane(packet, i, r);
  for (int i = 0; i < N; ++i) valid[i] = i < count ? -1 : 0;
  if constexpr (N == 16)
    rtcOccluded16(valid, scene, &context, &packet);
  else
    rtcOccluded8(valid, scene, &context, &packet);
  for (int i = 0; i < count; ++i) blocked[i] = packet.tfar[i] < 0.0f;
}

}  // namespace

void RayTracer::occluded(std::span<const ShadowRay> rays, uint8_t* blocked) const {
  // Sixteen rays at a time where more than eight remain: wider packets of incoherent rays still
  // share the top of the tree (AVX-512 traces them in one pass; narrower processors in two).
  for (size_t first = 0; first < rays.size();) {
    const size_t left = rays.size() - first, n = std::min<size_t>(left, left > 8 ? 16 : 8);
    if (n > 8)
      occluded_packet<16, RTCRay16>(handles_->scene, recorder_, rays.subspan(first, n),
                                    blocked + first);
    else
      occluded_packet<8, RTCRay8>(handles_->scene, recorder_, rays.subspan(first, n),
                                  blocked + first);
    first += n;
  }
}

size_t RayTracer::replay(const std::vector<RecordedRay>& rays) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  size_t hits = 0;
  for (const RecordedRay& r : rays) {
    if (r.closest) {
      alignas(16) RTCRayHit rh;
      rh.ray = embree_ray(r.origin, r.direction, r.tnear, r.tfar);
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(handles_->scene, &context, &rh);
      hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    } else {
      alignas(16) RTCRay ray = embree_ray(r.origin, r.direction, r.tnear, r.tfar);
      rtcOccluded1(handles_->scene, &context, &ray);
      hits += ray.tfar < 0.0f;
    }
  }
  return hits;
}

}  // namespace countershade
