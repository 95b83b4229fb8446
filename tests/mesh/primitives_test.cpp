#include "mesh/primitives.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <map>
#include <numbers>

namespace countershade {
namespace {

// Signed volume by the divergence theorem: positive when faces wind counter-clockwise outwards.
double signed_volume(const TriangleMesh& m) {
  double v = 0;
  for (const auto& t : m.triangles)
    v += glm::dot(glm::dvec3(m.positions[t.x]),
                  glm::cross(glm::dvec3(m.positions[t.y]), glm::dvec3(m.positions[t.z]))) /
         6.0;
  return v;
}

// Closed and consistently oriented: every directed edge appears once and its reverse once.
bool closed_and_oriented(const TriangleMesh& m) {
  std::map<std::pair<unsigned, unsigned>, int> edges;
  for (const auto& t : m.triangles)
    for (int c = 0; c < 3; ++c) ++edges[{t[c], t[(c + 1) % 3]}];
  for (const auto& [e, count] : edges)
    if (count != 1 || edges.count({e.second, e.first}) == 0 || edges.at({e.second, e.first}) != 1)
      return false;
  return true;
}

TEST(Primitives, BoxesAreClosedWeldedAndHaveTheRightVolume) {
  // A bevelled (chamfered) box is the Minkowski sum of the inner box with a ball (octahedron) of
  // radius r: inner volume + faces·r + edges·(quarter disc | quarter diamond) + corners.
  const double a = 2.0, b = 1.0, c = 0.5, r = 0.1;
  const double ia = a - 2 * r, ib = b - 2 * r, ic = c - 2 * r;
  const double faces = ia * ib * ic + 2 * r * (ia * ib + ib * ic + ia * ic);
  const double edge_sum = 4 * (ia + ib + ic);
  const double expected[] = {
      a * b * c,
      faces + edge_sum * std::numbers::pi * r * r / 4 + 4.0 / 3.0 * std::numbers::pi * r * r * r,
      faces + edge_sum * r * r / 2 + 4.0 / 3.0 * r * r * r};
  int i = 0;
  for (EdgeProfile profile : {EdgeProfile::sharp, EdgeProfile::bevel, EdgeProfile::chamfer}) {
    TriangleMesh box = make_box({a, b, c}, profile, r, 4, 16);
    EXPECT_TRUE(closed_and_oriented(box)) << int(profile);
    // The bevel's quarter circles are tessellated with 4 segments, so allow 0.5%.
    EXPECT_NEAR(signed_volume(box), expected[i], 0.005 * expected[i]) << int(profile);
    ++i;
  }
}

TEST(Primitives, SphereAndCylinderVolumes) {
  TriangleMesh sphere = make_sphere(1.5, 5);
  EXPECT_TRUE(closed_and_oriented(sphere));
  EXPECT_EQ(sphere.triangle_count(), 20u * 1024u);
  EXPECT_NEAR(signed_volume(sphere), 4.0 / 3.0 * std::numbers::pi * std::pow(1.5, 3), 0.01 * 14.1);
  for (const auto& p : sphere.positions) EXPECT_NEAR(glm::length(p), 1.5f, 1e-5f);

  TriangleMesh cylinder = make_cylinder(0.5, 2.0, 96);
  EXPECT_TRUE(closed_and_oriented(cylinder));
  EXPECT_NEAR(signed_volume(cylinder), std::numbers::pi * 0.25 * 2.0, 0.01 * 1.571);
}

TEST(Primitives, PlaneFacesUpWithUnitUvs) {
  TriangleMesh plane = make_plane(4.0, 8);
  EXPECT_EQ(plane.triangle_count(), 128u);
  compute_corner_normals(plane, 180.0);
  for (const auto& n : plane.corner_normals) EXPECT_NEAR(n.y, 1.0f, 1e-6f);
  for (const auto& uv : plane.corner_uvs) {
    EXPECT_GE(uv.x, 0.0f);
    EXPECT_LE(uv.y, 1.0f);
  }
}

// A disc is flat, faces up, covers πr² (up to its polygon's area) and has one boundary: its rim,
// every vertex of which lies at the radius.
TEST(Primitives, DiscIsAFlatOpenCapFacingUp) {
  const double r = 0.045;
  const int n = 48;
  TriangleMesh disc = make_disc(r, n);
  double area = 0;
  for (const auto& t : disc.triangles) {
    const glm::dvec3 a(disc.positions[t.x]), b(disc.positions[t.y]), c(disc.positions[t.z]);
    const glm::dvec3 normal = glm::cross(b - a, c - a);
    EXPECT_GT(normal.y, 0.0);  // counter-clockwise seen from +y
    area += 0.5 * glm::length(normal);
  }
  EXPECT_NEAR(area, 0.5 * n * r * r * std::sin(2 * std::numbers::pi / n), 1e-9);
  for (const auto& p : disc.positions) {
    EXPECT_EQ(p.y, 0.0f);
    EXPECT_LE(glm::length(p), r * (1 + 1e-6));
  }
  std::map<std::pair<unsigned, unsigned>, int> edges;
  for (const auto& t : disc.triangles)
    for (int c = 0; c < 3; ++c)
      ++edges[{std::min(t[c], t[(c + 1) % 3]), std::max(t[c], t[(c + 1) % 3])}];
  int rim = 0;
  for (const auto& [e, count] : edges) {
    EXPECT_LE(count, 2);
    if (count == 1) {
      ++rim;
      EXPECT_NEAR(glm::length(disc.positions[e.first]), r, 1e-7);
      EXPECT_NEAR(glm::length(disc.positions[e.second]), r, 1e-7);
    }
  }
  EXPECT_EQ(rim, n);
  EXPECT_EQ(disc.triangle_count(), size_t(n) * (2 * 8 - 1));  // round(48/2π) = 8 rings
}

// The relief is the plane with each vertex raised by the height field; its two parts have the
// sizes and wavelength the docs give, and both vary smoothly from vertex to vertex.
TEST(Primitives, ReliefRaisesThePlaneByItsHeightField) {
  const TriangleMesh plane = make_plane(2.0, 64), relief = make_relief(2.0, 64, 0.1, 0.02);
  ASSERT_EQ(relief.positions.size(), plane.positions.size());
  EXPECT_EQ(relief.triangles, plane.triangles);
  double lowest = 0, highest = 0;
  for (size_t i = 0; i < relief.positions.size(); ++i) {
    const glm::vec3 p = plane.positions[i], q = relief.positions[i];
    EXPECT_EQ(q.x, p.x);
    EXPECT_EQ(q.z, p.z);
    const double u = p.x / 2.0 + 0.5, v = p.z / 2.0 + 0.5;
    EXPECT_NEAR(q.y, 0.1 * relief_coarse(u, v) + 0.02 * relief_fine(u, v), 1e-6);
    lowest = std::min(lowest, double(q.y)), highest = std::max(highest, double(q.y));
  }
  EXPECT_GT(highest, 0.08);  // the highest hill, 1.0 × 0.1 at its centre
  EXPECT_LT(lowest, -0.05);  // the deepest valley, −0.7 × 0.1
  EXPECT_NEAR(relief_coarse(0.25, 0.30), 1.0, 0.05);
  // The ridges: circles around (−0.35, 1.25), of wavelength 1/14 along every radius.
  for (double angle : {-1.2, -0.9, -0.5}) {
    const double du = std::cos(angle), dv = std::sin(angle);
    for (double r : {0.5, 0.8, 1.1}) {
      const double f = relief_fine(-0.35 + r * du, 1.25 + r * dv);
      EXPECT_NEAR(relief_fine(-0.35 + (r + 1.0 / 14.0) * du, 1.25 + (r + 1.0 / 14.0) * dv), f,
                  1e-9);
      EXPECT_NEAR(relief_fine(-0.35 + (r + 0.5 / 14.0) * du, 1.25 + (r + 0.5 / 14.0) * dv), -f,
                  1e-9);
      EXPECT_NEAR(relief_fine(-0.35 + r * std::cos(angle + 0.1), 1.25 + r * std::sin(angle + 0.1)),
                  f, 1e-9);
    }
  }
  // Smooth: on a fine lattice no step is larger than the steepest slope allows.
  const double h = 1e-3, steepest = 2 * std::numbers::pi * 14.0 * 1.01;
  for (int j = 0; j < 200; ++j)
    for (int i = 0; i < 200; ++i) {
      const double u = i / 200.0, v = j / 200.0;
      EXPECT_LT(std::abs(relief_fine(u + h, v) - relief_fine(u, v)), steepest * h);
      EXPECT_LT(std::abs(relief_coarse(u, v + h) - relief_coarse(u, v)), 20.0 * h);
    }
  // No relief: the plane itself.
  EXPECT_EQ(make_relief(2.0, 64, 0.0, 0.0).positions, plane.positions);
}

TEST(Primitives, CreaseAngleSplitsBoxNormalsButKeepsVerticesShared) {
  TriangleMesh box = make_box({1, 1, 1}, EdgeProfile::sharp, 0, 1, 4);
  compute_corner_normals(box, 30.0);
  // Every corner normal is one of the six axis directions.
  for (const auto& n : box.corner_normals)
    EXPECT_NEAR(std::abs(n.x) + std::abs(n.y) + std::abs(n.z), 1.0f, 1e-6f);
  EXPECT_EQ(box.vertex_count(), 6u * 25u - 12u * 5u + 8u);  // welded lattice points on the surface
}

}  // namespace
}  // namespace countershade
