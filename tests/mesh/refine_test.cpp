#include "mesh/refine.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "mesh/adjacency.h"
#include "mesh/primitives.h"

namespace countershade {
namespace {

double area(const TriangleMesh& m) {
  double a = 0;
  for (size_t t = 0; t < m.triangle_count(); ++t) a += triangle_double_area(m, t) / 2;
  return a;
}

TEST(Refine, SplitsUntilNoEdgeIsLongerThanTheTarget) {
  TriangleMesh box = make_box({2, 1, 1}, EdgeProfile::sharp, 0, 1, 1);
  compute_corner_normals(box, 30.0);
  std::vector<float> weights(box.vertex_count(), 2.0f);
  double before = area(box);
  size_t splits = refine_long_edges(box, 0.2, &weights);
  EXPECT_GT(splits, 50u);
  for (const auto& t : box.triangles)
    for (int c = 0; c < 3; ++c)
      EXPECT_LE(glm::length(box.positions[t[c]] - box.positions[t[(c + 1) % 3]]), 0.2f + 1e-6f);
  EXPECT_NEAR(area(box), before, 1e-4);
  EXPECT_EQ(weights.size(), box.vertex_count());
  for (float w : weights) EXPECT_FLOAT_EQ(w, 2.0f);
  // Still one welded, closed surface whose corner normals stay on the cube's axes (creases kept).
  EXPECT_EQ(connected_components(adjacency_from_triangles(box.vertex_count(), box.triangles)).count,
            1u);
  for (const auto& n : box.corner_normals)
    EXPECT_NEAR(std::abs(n.x) + std::abs(n.y) + std::abs(n.z), 1.0f, 1e-5f);
  std::map<std::pair<unsigned, unsigned>, int> directed;
  for (const auto& t : box.triangles)
    for (int c = 0; c < 3; ++c) ++directed[{t[c], t[(c + 1) % 3]}];
  for (const auto& [e, count] : directed) EXPECT_EQ(directed.count({e.second, e.first}), 1u);
}

TEST(Refine, InterpolatesUvsPerTriangle) {
  TriangleMesh plane = make_plane(1.0, 1);
  refine_long_edges(plane, 0.3);
  for (size_t t = 0; t < plane.triangle_count(); ++t)
    for (int c = 0; c < 3; ++c) {
      const auto& p = plane.positions[plane.triangles[t][c]];
      const auto& uv = plane.corner_uvs[3 * t + c];
      EXPECT_NEAR(uv.x, p.x + 0.5f, 1e-6f);
      EXPECT_NEAR(uv.y, 0.5f - p.z, 1e-6f);
    }
}

}  // namespace
}  // namespace countershade
