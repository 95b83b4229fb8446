#include "render/ray_tracer.h"

#include <embree3/rtcore.h>

#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace countershade {
namespace {

// Embree calls this from C code, so it records the error instead of throwing through it.
void embree_error(void* user, RTCError code, const char* message) {
  auto* error = static_cast<std::string*>(user);
  if (error->empty())
    *error = "Embree error " + std::to_string(int(code)) + ": " + (message ? message : "unknown");
}

}  // namespace

struct RayTracer::Handles {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
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
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.vertex_count()));
    for (size_t v = 0; v < mesh.vertex_count(); ++v)
      std::memcpy(vertices + 3 * v, &mesh.positions[v], 3 * sizeof(float));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh.triangle_count()));
    for (size_t t = 0; t < mesh.triangle_count(); ++t)
      std::memcpy(indices + 3 * t, &mesh.triangles[t], 3 * sizeof(unsigned));
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
  alignas(16) RTCRayHit rh;
  rh.ray.org_x = float(origin.x);
  rh.ray.org_y = float(origin.y);
  rh.ray.org_z = float(origin.z);
  rh.ray.dir_x = float(direction.x);
  rh.ray.dir_y = float(direction.y);
  rh.ray.dir_z = float(direction.z);
  rh.ray.tnear = float(tnear);
  rh.ray.tfar = float(std::min(tfar, double(std::numeric_limits<float>::max())));
  rh.ray.mask = 0xFFFFFFFF;
  rh.ray.flags = 0;
  rh.ray.time = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(handles_->scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  return Hit{rh.hit.geomID, rh.hit.primID, rh.hit.u, rh.hit.v, rh.ray.tfar};
}

bool RayTracer::occluded(const glm::dvec3& origin, const glm::dvec3& direction, double tnear,
                         double tfar) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  alignas(16) RTCRay ray;
  ray.org_x = float(origin.x);
  ray.org_y = float(origin.y);
  ray.org_z = float(origin.z);
  ray.dir_x = float(direction.x);
  ray.dir_y = float(direction.y);
  ray.dir_z = float(direction.z);
  ray.tnear = float(tnear);
  ray.tfar = float(std::min(tfar, double(std::numeric_limits<float>::max())));
  ray.mask = 0xFFFFFFFF;
  ray.flags = 0;
  ray.time = 0;
  rtcOccluded1(handles_->scene, &context, &ray);
  return ray.tfar < 0.0f;
}

}  // namespace countershade
