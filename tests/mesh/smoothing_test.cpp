#include "mesh/smoothing.h"

#include <gtest/gtest.h>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <cmath>

#include "mesh/mesh_io.h"
#include "mesh/primitives.h"
#include "test_util.h"

namespace countershade {
namespace {

TEST(Smoothing, IterationsFollowSigma) {
  EXPECT_EQ(iterations_for_sigma(1.0, 0.1), 200);  // 2σ²/h² = 2/0.01
  EXPECT_EQ(iterations_for_sigma(0.001, 0.1), 1);  // at least one step
  EXPECT_EQ(iterations_for_sigma(0.5, 0.1), 50);
}

// On a regular triangulated grid, n steps of the uniform Laplacian spread an impulse into a
// distribution whose standard deviation is the requested σ.
TEST(Smoothing, ImpulseSpreadMatchesRequestedSigma) {
  TriangleMesh grid = make_plane(1.0, 100);  // spacing h = 0.01, valence 6 inside
  VertexAdjacency adj = adjacency_from_triangles(grid.vertex_count(), grid.triangles);
  Components comps = connected_components(adj);
  double h = component_mean_edge_length(grid.positions, adj, comps)[0];
  for (double sigma : {0.04, 0.07}) {
    int n = iterations_for_sigma(sigma, h);
    std::vector<double> values(grid.vertex_count(), 0.0);
    size_t centre = 50 * 101 + 50;
    values[centre] = 1.0;
    laplacian_smooth(adj, comps.label, {n}, values);
    double mass = 0, mx = 0, mz = 0;
    for (size_t v = 0; v < values.size(); ++v) {
      mass += values[v];
      mx += values[v] * grid.positions[v].x;
      mz += values[v] * grid.positions[v].z;
    }
    mx /= mass;
    mz /= mass;
    double vx = 0, vz = 0;
    for (size_t v = 0; v < values.size(); ++v) {
      vx += values[v] * std::pow(grid.positions[v].x - mx, 2);
      vz += values[v] * std::pow(grid.positions[v].z - mz, 2);
    }
    double measured = std::sqrt((vx + vz) / (2 * mass));
    EXPECT_NEAR(measured, sigma, 0.1 * sigma) << "n = " << n;
    EXPECT_NEAR(mass, 1.0, 0.05);  // far from the border, the walk keeps (almost) all its mass
  }
}

// The noise model of the vertex signal's sampling: n steps reduce independent vertex errors by at
// least √(6n) (the sum of the squared weights of an interior vertex, ≤ 1/(6n), is the smoothed
// error's variance), and not by much more, so the vertex pass does not oversample either.
TEST(Smoothing, IndependentVertexErrorsShrinkBySqrtSixN) {
  TriangleMesh grid = make_plane(1.0, 100);
  VertexAdjacency adj = adjacency_from_triangles(grid.vertex_count(), grid.triangles);
  Components comps = connected_components(adj);
  for (int n : {1, 2, 4, 16, 64}) {
    std::vector<double> weights(grid.vertex_count(), 0.0);
    weights[50 * 101 + 50] = 1.0;
    laplacian_smooth(adj, comps.label, {n}, weights);
    double variance = 0;
    for (double w : weights) variance += w * w;
    EXPECT_LE(variance, 1.0 / (6.0 * n) + 1e-12) << "n = " << n;
    EXPECT_GE(variance, 0.7 / (6.0 * n)) << "n = " << n;
  }
}

// The CSR path against a naive double loop over OpenMesh's vertex-vertex circulators.
TEST(Smoothing, BunnyMatchesNaiveOpenMeshReference) {
  auto path = testing::mesh_path("stanford-bunny.obj");
  TriangleMesh mesh = load_mesh(path);
  OpenMesh::TriMesh_ArrayKernelT<> om;
  ASSERT_TRUE(OpenMesh::IO::read_mesh(om, path.string()));
  ASSERT_EQ(om.n_vertices(), mesh.vertex_count());

  std::vector<double> signal(mesh.vertex_count());
  for (size_t v = 0; v < signal.size(); ++v)
    signal[v] = 50.0 + 400.0 * mesh.positions[v].y + 10.0 * std::sin(3000.0 * mesh.positions[v].x);
  const int n = 12;

  std::vector<double> reference = signal, next(signal.size());
  for (int it = 0; it < n; ++it) {
    for (auto vh : om.vertices()) {
      double sum = 0;
      int count = 0;
      for (auto nb : om.vv_range(vh)) {
        sum += reference[size_t(nb.idx())];
        ++count;
      }
      next[size_t(vh.idx())] = count ? sum / count : reference[size_t(vh.idx())];
    }
    reference.swap(next);
  }

  VertexAdjacency adj = adjacency_from_triangles(mesh.vertex_count(), mesh.triangles);
  Components comps = connected_components(adj);
  std::vector<int> iterations(comps.count, n);
  std::vector<double> smoothed = signal;
  laplacian_smooth(adj, comps.label, iterations, smoothed, 2);
  for (size_t v = 0; v < signal.size(); ++v) ASSERT_NEAR(smoothed[v], reference[v], 1e-6) << v;
}

TEST(Smoothing, ComponentsNeverMixAndKeepTheirOwnIterationCounts) {
  // Two separate strips: 0-1-2 and 3-4-5 (as triangles 0,1,2 and 3,4,5).
  VertexAdjacency adj = adjacency_from_triangles(6, {{0, 1, 2}, {3, 4, 5}});
  Components comps = connected_components(adj);
  ASSERT_EQ(comps.count, 2u);
  std::vector<double> values = {100, 0, 0, 7, 7, 7};
  laplacian_smooth(adj, comps.label, {3, 50}, values);
  EXPECT_DOUBLE_EQ(values[3] + values[4] + values[5], 21.0);  // constant stays constant
  for (int v = 3; v < 6; ++v) EXPECT_DOUBLE_EQ(values[v], 7.0);
  EXPECT_NEAR(values[0] + values[1] + values[2], 100.0, 1e-12);
  // After 3 steps on a triangle: v0 = 25 (1 -> 0 -> 1/2 -> 1/4 of the initial mass pattern).
  EXPECT_DOUBLE_EQ(values[0], 25.0);
}

TEST(Smoothing, OneRingVarianceIsPopulationVariance) {
  VertexAdjacency adj = adjacency_from_triangles(3, {{0, 1, 2}});
  auto var = one_ring_variance(adj, {0.0, 0.3, 0.6});
  EXPECT_NEAR(var[0], 0.06, 1e-12);  // values 0, .3, .6: mean .3, population variance .06
}

}  // namespace
}  // namespace countershade
