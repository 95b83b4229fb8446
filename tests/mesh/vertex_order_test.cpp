#include "mesh/vertex_order.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <numeric>
#include <random>

#include "mesh/chebyshev_smoothing.h"
#include "mesh/primitives.h"
#include "mesh/smoothing.h"

namespace countershade {
namespace {

// A 460×460 grid (211,600 vertices, above kReorderAbove) with its vertices shuffled: a file order
// that scatters every ring.
struct ShuffledGrid {
  VertexAdjacency adjacency;
  std::vector<uint32_t> label;
};
ShuffledGrid shuffled_grid() {
  const TriangleMesh plane = make_plane(1.0, 459);
  std::vector<uint32_t> shuffle(plane.vertex_count());
  std::iota(shuffle.begin(), shuffle.end(), 0u);
  std::shuffle(shuffle.begin(), shuffle.end(), std::mt19937(7));
  const VertexAdjacency adjacency =
      renumbered(adjacency_from_triangles(plane.vertex_count(), plane.triangles), shuffle);
  return {adjacency, connected_components(adjacency).label};
}

// The largest index distance along an edge.
uint32_t bandwidth(const VertexAdjacency& adjacency) {
  uint32_t widest = 0;
  for (uint32_t v = 0; v < adjacency.vertex_count(); ++v)
    for (uint32_t w : adjacency.of(v)) widest = std::max(widest, v > w ? v - w : w - v);
  return widest;
}

TEST(VertexOrder, BreadthFirstOrderKeepsEveryRingWithinAFewWavefronts) {
  const ShuffledGrid grid = shuffled_grid();
  ASSERT_GT(grid.adjacency.vertex_count(), kReorderAbove);
  const std::vector<uint32_t> order = breadth_first_order(grid.adjacency);
  std::vector<uint32_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (uint32_t i = 0; i < sorted.size(); ++i) ASSERT_EQ(sorted[i], i) << "not a permutation";
  // Shuffled, neighbours lie anywhere; breadth first, within about two wavefronts of the search
  // (a layer of the grid is at most about 2·460 vertices long; measured: 820).
  EXPECT_GT(bandwidth(grid.adjacency), 200000u);
  const uint32_t local = bandwidth(renumbered(grid.adjacency, order));
  EXPECT_LT(local, 2000u);
}

TEST(VertexOrder, SmoothingInBreadthFirstOrderGivesTheSameBitsAsTheGivenOrder) {
  const ShuffledGrid grid = shuffled_grid();
  std::vector<double> signal(grid.adjacency.vertex_count());
  std::mt19937 random(3);
  for (double& v : signal) v = std::uniform_real_distribution<double>(0, 100)(random);
  for (SmoothingScheme scheme : {SmoothingScheme::iterate, SmoothingScheme::chebyshev}) {
    std::vector<double> given = signal, reordered = signal;
    if (scheme == SmoothingScheme::iterate)
      laplacian_smooth(grid.adjacency, grid.label, {kReorderSteps}, given, 2);
    else
      chebyshev_smooth(grid.adjacency, grid.label, {kReorderSteps}, given, 2);
    smooth_over_rings(grid.adjacency, grid.label, {kReorderSteps}, reordered, scheme, 2);
    EXPECT_EQ(given, reordered);
    EXPECT_NE(given, signal);
  }
}

// Four signals smoothed side by side (usm3d's noise probes) give each one's own numbers, in either
// scheme, in breadth-first order as well as in the given one.
TEST(VertexOrder, FourSignalsAtOnceGiveEachOnesOwnBits) {
  const ShuffledGrid grid = shuffled_grid();
  const size_t n = grid.adjacency.vertex_count();
  std::mt19937 random(5);
  std::vector<glm::dvec4> four(n);
  for (glm::dvec4& v : four)
    for (int c = 0; c < 4; ++c) v[c] = std::uniform_real_distribution<double>(-1, 1)(random);
  for (SmoothingScheme scheme : {SmoothingScheme::iterate, SmoothingScheme::chebyshev})
    for (int steps : {9, kReorderSteps}) {
      std::vector<glm::dvec4> together = four;
      smooth_over_rings(grid.adjacency, grid.label, {steps}, together, scheme, 2);
      for (int c = 0; c < 4; ++c) {
        std::vector<double> alone(n), from(n);
        for (size_t v = 0; v < n; ++v) alone[v] = from[v] = four[v][c];
        smooth_over_rings(grid.adjacency, grid.label, {steps}, alone, scheme, 2);
        size_t same = 0;
        for (size_t v = 0; v < n; ++v) same += together[v][c] == alone[v];
        EXPECT_EQ(same, n) << "signal " << c << ", " << steps << " steps";
        EXPECT_NE(alone, from);
      }
    }
}

}  // namespace
}  // namespace countershade
