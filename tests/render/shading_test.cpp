// Where shadow rays start: on the smooth surface that the corner normals describe, so that a
// terminator follows the shading normal instead of the mesh's facets.

#include "render/shading.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

namespace countershade {
namespace {

// One triangle in the plane z = 0 with the given corner normals.
Scene one_triangle(const glm::vec3& n0, const glm::vec3& n1, const glm::vec3& n2) {
  Scene scene;
  Object object;
  object.mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  object.mesh.triangles = {{0, 1, 2}};
  object.mesh.corner_normals = {glm::normalize(n0), glm::normalize(n1), glm::normalize(n2)};
  scene.objects.push_back(std::move(object));
  return scene;
}

// Corner normals tilted away from the triangle's centre, as on a convex surface.
Scene convex_triangle() {
  return one_triangle({-0.3f, -0.3f, 1}, {0.5f, -0.2f, 1}, {-0.2f, 0.5f, 1});
}

TEST(ShadowOrigin, LiftsAPointOfAConvexFacetOntoTheCornersTangentPlanes) {
  const Scene scene = convex_triangle();
  const SurfacePoint p = surface_point(scene, 0, 0, 0.3, 0.3);
  const glm::dvec3 o = shadow_origin(scene, p, false);
  // Hanika (2021): the barycentric mean of the point's projections onto the corners' tangent
  // planes, each only where the point lies below that plane. Here it lies below all three.
  const TriangleMesh& mesh = scene.objects[0].mesh;
  const double b[3] = {0.4, 0.3, 0.3};
  glm::dvec3 expected(0.0);
  for (int k = 0; k < 3; ++k) {
    const glm::dvec3 n(mesh.corner_normals[k]), d = p.position - glm::dvec3(mesh.positions[k]);
    ASSERT_LT(glm::dot(d, n), 0.0);
    expected += b[k] * (p.position - glm::dot(d, n) * n);
  }
  EXPECT_LT(glm::length(o - expected), 1e-12);
  EXPECT_GT(o.z, 0.05);  // above the facet, on the side the normals point to
}

TEST(ShadowOrigin, LeavesCornersFlatFacetsAndConcaveOrBackSidesWhereTheyAre) {
  const Scene convex = convex_triangle();
  for (auto [b1, b2] : {std::pair{0.0, 0.0}, std::pair{1.0, 0.0}, std::pair{0.0, 1.0}}) {
    const SurfacePoint corner = surface_point(convex, 0, 0, b1, b2);
    EXPECT_EQ(shadow_origin(convex, corner, false), corner.position);
  }
  // Seen from behind, the convex facet is concave: rays from it cannot hit its neighbours.
  const SurfacePoint inside = surface_point(convex, 0, 0, 0.3, 0.3);
  EXPECT_EQ(shadow_origin(convex, inside, true), inside.position);
  const Scene flat = one_triangle({0, 0, 1}, {0, 0, 1}, {0, 0, 1});
  const SurfacePoint p = surface_point(flat, 0, 0, 0.2, 0.5);
  EXPECT_EQ(shadow_origin(flat, p, false), p.position);
  const Scene concave = one_triangle({0.3f, 0.3f, 1}, {-0.5f, 0.2f, 1}, {0.2f, -0.5f, 1});
  const SurfacePoint q = surface_point(concave, 0, 0, 0.3, 0.3);
  EXPECT_EQ(shadow_origin(concave, q, false), q.position);
}

}  // namespace
}  // namespace countershade
