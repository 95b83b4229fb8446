#include "render/ray_differentials.h"

#include <cmath>
#include <glm/geometric.hpp>

namespace countershade {
namespace {

// The offset from the hit to where `ray` meets the tangent plane at the hit; false if it misses.
bool offset_on_plane(const SurfacePoint& sp, const Ray& ray, glm::dvec3& offset) {
  const double facing = glm::dot(ray.direction, sp.geometric_normal);
  if (std::abs(facing) < 1e-12) return false;
  const double t = glm::dot(sp.position - ray.origin, sp.geometric_normal) / facing;
  if (!(t > 0) || !std::isfinite(t)) return false;
  offset = ray.origin + t * ray.direction - sp.position;
  return true;
}

}  // namespace

void set_uv_differentials(const Scene& scene, const Ray& right, const Ray& down, SurfacePoint& sp) {
  const TriangleMesh& mesh = scene.objects[sp.object].mesh;
  if (!mesh.has_uvs()) return;
  glm::dvec3 dx, dy;
  if (!offset_on_plane(sp, right, dx) || !offset_on_plane(sp, down, dy)) return;
  const glm::uvec3& tri = mesh.triangles[sp.triangle];
  const glm::dvec3 e1 = glm::dvec3(mesh.positions[tri.y]) - glm::dvec3(mesh.positions[tri.x]);
  const glm::dvec3 e2 = glm::dvec3(mesh.positions[tri.z]) - glm::dvec3(mesh.positions[tri.x]);
  // Barycentric offsets (b1, b2) of a vector in the triangle's plane: the normal equations of
  // offset = b1·e1 + b2·e2.
  const double a = glm::dot(e1, e1), b = glm::dot(e1, e2), c = glm::dot(e2, e2),
               det = a * c - b * b;
  if (!(std::abs(det) > 0)) return;
  const size_t corner = 3 * size_t(sp.triangle);
  const glm::dvec2 uv0(mesh.corner_uvs[corner]);
  const glm::dvec2 du1 = glm::dvec2(mesh.corner_uvs[corner + 1]) - uv0,
                   du2 = glm::dvec2(mesh.corner_uvs[corner + 2]) - uv0;
  auto uv_offset = [&](const glm::dvec3& offset) {
    const double p = glm::dot(e1, offset), q = glm::dot(e2, offset);
    return ((c * p - b * q) / det) * du1 + ((a * q - b * p) / det) * du2;
  };
  sp.duv_dx = uv_offset(dx);
  sp.duv_dy = uv_offset(dy);
}

}  // namespace countershade
