// Smoothing by the truncated Chebyshev expansion of A^n equals n plain 1-ring steps within 1e-4 of
// the signal's range (a test at n = 10, 100 and 1000 on the bunny, with a signal that has detail
// at every scale), keeps components apart with their own step counts, and needs O(√n) products.

#include "mesh/chebyshev_smoothing.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "enhance/usm3d.h"
#include "mesh/mesh_io.h"
#include "mesh/smoothing.h"
#include "mesh/surface_graph.h"
#include "test_util.h"

namespace countershade {
namespace {

TEST(ChebyshevSmoothing, TheCoefficientsExpandAPower) {
  // x^n = Σ c_k T_k(x) exactly when nothing is dropped; check at points of [−1, 1].
  for (int n : {0, 1, 2, 5, 12}) {
    const std::vector<double> c = power_chebyshev_coefficients(n, 0.0);
    ASSERT_EQ(c.size(), size_t(n) + 1);
    for (double x : {-1.0, -0.6, 0.0, 0.3, 0.9, 1.0}) {
      double sum = 0;
      for (size_t k = 0; k < c.size(); ++k) sum += c[k] * std::cos(double(k) * std::acos(x));
      EXPECT_NEAR(sum, std::pow(x, n), 1e-12) << n << " " << x;
    }
  }
  // Truncated: the degree grows as √n and the dropped weight stays below the tail.
  for (int n : {100, 1000, 10000}) {
    const std::vector<double> c = power_chebyshev_coefficients(n, 1e-7);
    double kept = 0;
    for (double v : c) kept += v;
    EXPECT_GE(kept, 1 - 1e-7) << n;
    EXPECT_LE(double(c.size()), std::sqrt(2.0 * n * std::log(2 / 1e-7)) + 2) << n;
  }
}

TEST(ChebyshevSmoothing, EqualsThePlainIterationsWithinATenThousandthOfTheRange) {
  const TriangleMesh mesh = load_mesh(testing::mesh_path("stanford-bunny.obj"));
  const VertexAdjacency adjacency = adjacency_from_triangles(mesh.vertex_count(), mesh.triangles);
  const Components components = connected_components(adjacency);
  std::vector<double> signal(mesh.vertex_count());
  for (size_t v = 0; v < signal.size(); ++v)
    signal[v] = 50.0 + 400.0 * mesh.positions[v].y + 10.0 * std::sin(3000.0 * mesh.positions[v].x);
  const auto [lo, hi] = std::minmax_element(signal.begin(), signal.end());
  const double range = *hi - *lo;
  for (int n : {10, 100, 1000}) {
    std::vector<double> iterated = signal, expanded = signal;
    const std::vector<int> steps(components.count, n);
    laplacian_smooth(adjacency, components.label, steps, iterated, 2);
    chebyshev_smooth(adjacency, components.label, steps, expanded, 2);
    double largest = 0, moved = 0;
    for (size_t v = 0; v < signal.size(); ++v) {
      largest = std::max(largest, std::abs(expanded[v] - iterated[v]));
      moved = std::max(moved, std::abs(iterated[v] - signal[v]));
    }
    EXPECT_LT(largest, 1e-4 * range) << "n = " << n;
    EXPECT_GT(moved, 0.01 * range) << "n = " << n;  // the smoothing did something to match
  }
}

TEST(ChebyshevSmoothing, ComponentsKeepTheirOwnStepCounts) {
  const VertexAdjacency adjacency =
      adjacency_from_triangles(7, {{0, 1, 2}, {3, 4, 5}});  // vertex 6 alone
  const Components components = connected_components(adjacency);
  ASSERT_EQ(components.count, 3u);
  std::vector<double> values = {100, 0, 0, 7, 8, 9, 42}, expected = values;
  std::vector<int> steps(3);
  steps[components.label[0]] = 3, steps[components.label[3]] = 50, steps[components.label[6]] = 20;
  laplacian_smooth(adjacency, components.label, steps, expected);
  chebyshev_smooth(adjacency, components.label, steps, values);
  for (size_t v = 0; v < values.size(); ++v) EXPECT_NEAR(values[v], expected[v], 1e-5) << v;
  EXPECT_NEAR(values[0], 25.0, 1e-5);  // 3 steps on a triangle
  EXPECT_NEAR(values[6], 42.0, 1e-5);  // no neighbours: kept
}

// Below about 20 steps the expansion keeps every term (degree n, n + 1 products), so the scheme
// takes the n plain steps instead: the very same numbers. From there on it expands.
TEST(ChebyshevSmoothing, ShortSmoothingsTakeThePlainSteps) {
  const TriangleMesh mesh = load_mesh(testing::mesh_path("stanford-bunny.obj"));
  const VertexAdjacency adjacency = adjacency_from_triangles(mesh.vertex_count(), mesh.triangles);
  const Components components = connected_components(adjacency);
  std::vector<double> signal(mesh.vertex_count());
  for (size_t v = 0; v < signal.size(); ++v)
    signal[v] = 50.0 + 10.0 * std::sin(3000.0 * mesh.positions[v].x);
  for (int n : {1, 9, 20, 40}) {
    const std::vector<int> steps(components.count, n);
    std::vector<double> plain = signal, chosen = signal, expanded = signal;
    laplacian_smooth(adjacency, components.label, steps, plain, 2);
    chebyshev_smooth(adjacency, components.label, steps, expanded, 2);
    smooth_over_rings(adjacency, components.label, steps, chosen, SmoothingScheme::chebyshev, 2);
    const bool expands = power_chebyshev_coefficients(n).size() < size_t(n);
    EXPECT_EQ(expands, n >= 40) << n;
    EXPECT_EQ(chosen, expands ? expanded : plain) << n;
    // Past one step the two differ in rounding, so the comparison above tells them apart.
    if (n > 1) {
      EXPECT_NE(expanded, plain) << n;
    }
  }
}

// usm3d's per-vertex steps take the scheme from its width (`smoothing` in experiments).
TEST(ChebyshevSmoothing, Usm3dSmoothsTheSameEitherWay) {
  const TriangleMesh mesh = load_mesh(testing::mesh_path("stanford-bunny.obj"));
  const SurfaceGraph surface = surface_graph(mesh.positions, mesh.triangles);
  std::vector<double> lightness(mesh.vertex_count());
  for (size_t v = 0; v < lightness.size(); ++v)
    lightness[v] = 50 + 40 * std::sin(200.0 * mesh.positions[v].y);
  SmoothingWidth width{std::nullopt, 300, true};
  const SurfaceContrast iterated = surface_contrast(surface, lightness, {}, width);
  width.scheme = SmoothingScheme::chebyshev;
  const SurfaceContrast expanded = surface_contrast(surface, lightness, {}, width);
  double largest = 0, moved = 0;
  for (size_t v = 0; v < lightness.size(); ++v) {
    largest =
        std::max(largest, std::abs(expanded.smooth_lightness[v] - iterated.smooth_lightness[v]));
    moved = std::max(moved, std::abs(iterated.smooth_lightness[v] - lightness[v]));
  }
  EXPECT_LT(largest, 1e-4 * 80);
  EXPECT_GT(moved, 10.0);
}

}  // namespace
}  // namespace countershade
