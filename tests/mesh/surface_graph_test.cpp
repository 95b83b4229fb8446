// Welding for the 1-ring: smoothing crosses UV and normal seams, and polygon meshes use the 1-ring
// of their triangulation.

#include "mesh/surface_graph.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "enhance/usm3d.h"
#include "mesh/primitives.h"
#include "mesh/smoothing.h"

namespace countershade {
namespace {

// The plane with every vertex of the column x = 0 duplicated: triangles left of the seam use the
// originals, those right of it the copies (same positions, separate vertices), as a mesh split
// along a UV seam is stored.
TriangleMesh split_along_seam(const TriangleMesh& welded, std::vector<uint32_t>* copy_of) {
  TriangleMesh split = welded;
  copy_of->assign(welded.vertex_count(), UINT32_MAX);
  for (uint32_t v = 0; v < welded.vertex_count(); ++v)
    if (std::abs(welded.positions[v].x) < 1e-6f) {
      (*copy_of)[v] = uint32_t(split.positions.size());
      split.positions.push_back(welded.positions[v]);
    }
  for (auto& t : split.triangles) {
    const float centre_x =
        (welded.positions[t.x].x + welded.positions[t.y].x + welded.positions[t.z].x) / 3.0f;
    if (centre_x <= 0) continue;
    for (int c = 0; c < 3; ++c)
      if ((*copy_of)[t[c]] != UINT32_MAX) t[c] = (*copy_of)[t[c]];
  }
  return split;
}

// Pairs of points in random directions at 0.999 and 1.001 tolerances apart, anywhere in the grid
// of cells (across cell corners too): the first pairs are one surface point, the second are not.
TEST(SurfaceGraph, WeldingJoinsPointsWithinTheToleranceAndNoOthers) {
  std::mt19937 random(11);
  std::uniform_real_distribution<float> anywhere(-1, 1);
  std::normal_distribution<float> direction(0, 1);
  const double tolerance = 1e-3;
  for (double apart : {0.999, 1.001}) {
    std::vector<glm::vec3> positions;
    std::vector<std::pair<uint32_t, uint32_t>> edges;
    for (int k = 0; k < 2000; ++k) {
      const glm::vec3 p(anywhere(random), anywhere(random), anywhere(random));
      const glm::vec3 d =
          glm::normalize(glm::vec3(direction(random), direction(random), direction(random)));
      positions.push_back(p);
      positions.push_back(glm::vec3(glm::dvec3(p) + apart * tolerance * glm::dvec3(d)));
    }
    const SurfaceGraph g = surface_graph(positions, edges, tolerance);
    size_t joined = 0;
    for (size_t k = 0; k < positions.size(); k += 2) joined += g.point_of[k] == g.point_of[k + 1];
    EXPECT_EQ(joined, apart < 1 ? 2000u : 0u) << apart;
  }
}

// Two loose triangles, sides 3-4-5 and an equilateral one of side 2: each component's mean edge
// length is its own, and measuring at doubled positions doubles them.
TEST(SurfaceGraph, EachComponentKnowsItsMeanEdgeLength) {
  std::vector<glm::vec3> positions = {{0, 0, 0},  {3, 0, 0},  {0, 4, 0},
                                      {10, 0, 0}, {12, 0, 0}, {11, float(std::sqrt(3.0)), 0}};
  SurfaceGraph g = surface_graph(positions, std::vector<glm::uvec3>{{0, 1, 2}, {3, 4, 5}});
  ASSERT_EQ(g.components.count, 2u);
  ASSERT_EQ(g.mean_edge_length.size(), 2u);
  const uint32_t right = g.components.label[g.point_of[0]],
                 equilateral = g.components.label[g.point_of[3]];
  EXPECT_NEAR(g.mean_edge_length[right], 4.0, 1e-6);
  EXPECT_NEAR(g.mean_edge_length[equilateral], 2.0, 1e-6);
  for (auto& p : positions) p *= 2.0f;
  measure_edges(g, positions);
  EXPECT_NEAR(g.mean_edge_length[right], 8.0, 1e-6);
  EXPECT_NEAR(g.mean_edge_length[equilateral], 4.0, 1e-6);
}

// Without welded vertices a point is its vertex: the values pass through unchanged both ways.
TEST(SurfaceGraph, WithoutWeldsPointsAreVertices) {
  const TriangleMesh plane = make_plane(2.0, 4);
  const SurfaceGraph g = surface_graph(plane.positions, plane.triangles);
  ASSERT_EQ(g.point_count(), plane.vertex_count());
  std::vector<double> values(plane.vertex_count());
  for (size_t v = 0; v < values.size(); ++v) values[v] = 0.25 * double(v) - 3.0;
  EXPECT_EQ(g.to_points(values), values);
  EXPECT_EQ(g.to_vertices(values), values);
}

TEST(SurfaceGraph, ASeamDoesNotStopTheSmoothing) {
  const TriangleMesh welded = make_plane(1.0, 20);
  std::vector<uint32_t> copy_of;
  const TriangleMesh split = split_along_seam(welded, &copy_of);
  ASSERT_GT(split.vertex_count(), welded.vertex_count());
  // Without welding the seam cuts the plane in two.
  EXPECT_EQ(
      connected_components(adjacency_from_triangles(split.vertex_count(), split.triangles)).count,
      2u);
  // A step in lightness across the plane, the same at a vertex and at its copy.
  auto step = [](const glm::vec3& p) { return p.z < 0 ? 30.0 : 70.0; };
  std::vector<double> a(welded.vertex_count()), b(split.vertex_count());
  for (size_t v = 0; v < a.size(); ++v) a[v] = step(welded.positions[v]);
  for (size_t v = 0; v < b.size(); ++v) b[v] = step(split.positions[v]);
  SmoothingWidth width;
  width.sigma = 0.15;
  const SurfaceGraph ga = surface_graph(welded.positions, welded.triangles);
  const SurfaceGraph gb = surface_graph(split.positions, split.triangles);
  EXPECT_EQ(gb.point_count(), ga.point_count());
  EXPECT_EQ(gb.components.count, 1u);
  SurfaceContrast sa = surface_contrast(ga, a, {}, width);
  SurfaceContrast sb = surface_contrast(gb, b, {}, width);
  for (size_t v = 0; v < welded.vertex_count(); ++v) {
    EXPECT_DOUBLE_EQ(sb.smooth_lightness[v], sa.smooth_lightness[v]) << v;
    EXPECT_DOUBLE_EQ(sb.gain_factor[v], sa.gain_factor[v]) << v;
    if (copy_of[v] != UINT32_MAX) {
      EXPECT_DOUBLE_EQ(sb.smooth_lightness[copy_of[v]], sa.smooth_lightness[v]) << v;
    }
  }
}

// On a quad grid a checkerboard flips sign at every averaging step over the quads' sides (each
// neighbour has the other colour), so it never decays. The triangulated 1-ring adds a diagonal of
// the same colour, and the pattern fades.
TEST(SurfaceGraph, PolygonsUseTheTriangulated1Ring) {
  const int n = 16;
  std::vector<glm::vec3> positions;
  std::vector<std::vector<uint32_t>> quads;
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) positions.emplace_back(float(x), float(y), 0.0f);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const uint32_t v = uint32_t(y * (n + 1) + x);
      quads.push_back({v, v + 1, v + uint32_t(n) + 2, v + uint32_t(n) + 1});
    }
  std::vector<double> checker(positions.size());
  for (size_t v = 0; v < positions.size(); ++v)
    checker[v] = (int(positions[v].x) + int(positions[v].y)) % 2 ? 1.0 : -1.0;
  auto after = [&](const std::vector<std::pair<uint32_t, uint32_t>>& edges) {
    const SurfaceGraph g = surface_graph(positions, edges);
    std::vector<double> values = checker;
    laplacian_smooth(g.adjacency, g.components.label, {20}, values);
    double interior = 0;
    for (size_t v = 0; v < positions.size(); ++v)
      if (positions[v].x > 2 && positions[v].x < n - 2 && positions[v].y > 2 &&
          positions[v].y < n - 2)
        interior = std::max(interior, std::abs(values[v]));
    return interior;
  };
  std::vector<std::pair<uint32_t, uint32_t>> sides;
  for (const auto& q : quads)
    for (size_t i = 0; i < 4; ++i) sides.emplace_back(q[i], q[(i + 1) % 4]);
  EXPECT_GT(after(sides), 0.99) << "the quad 1-ring never smooths a checkerboard";
  PolygonSoup soup;
  for (const auto& q : quads) soup.add_face(q);
  EXPECT_LT(after(triangulated_edges(soup)), 0.1);
}

}  // namespace
}  // namespace countershade
