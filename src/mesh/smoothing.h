#pragma once
// Uniform Laplacian smoothing over the 1-ring, iterated (Ritschel et al. 2008, §5), and the
// quantities 3D unsharp masking derives from a per-vertex signal.

#include <cstdint>
#include <glm/vec4.hpp>
#include <vector>

#include "mesh/adjacency.h"
#include "mesh/triangle_mesh.h"

namespace countershade {

// The most smoothing iterations a width may ask for: a million 1-ring steps take minutes on a
// large mesh; beyond that a σ is a mistake (or wants a coarser mesh), not a stimulus.
inline constexpr double kMaxSmoothingIterations = 1e6;

// n = max(1, round(2σ²/h̄²)): on a regular triangulation each averaging step spreads a signal by
// h̄²/2 per axis, so n steps give a spread of σ. Throws InputError above kMaxSmoothingIterations.
int iterations_for_sigma(double sigma, double mean_edge_length);

// Smooths `values` (#V) in place: v_i <- mean of v_j over the 1-ring (v_i itself excluded),
// Jacobi style. Vertex v takes part in the first iterations[label[v]] steps and keeps its value
// after that, so components with different iteration counts are smoothed independently (no edge
// joins two components, so nothing leaks between them). Vertices without neighbours keep their
// value. `threads` = 0 uses all cores.
void laplacian_smooth(const VertexAdjacency& adjacency, const std::vector<uint32_t>& label,
                      const std::vector<int>& iterations, std::vector<double>& values,
                      int threads = 0);

// How the n steps are taken: one product with the 1-ring average per step, or the truncated
// Chebyshev expansion of the n-th power (mesh/chebyshev_smoothing.h: O(√n) products, within
// 1e-7 of the signal's range of the steps).
enum class SmoothingScheme { iterate, chebyshev };

// From this many vertices and steps on, smooth_over_rings works in breadth-first order
// (mesh/vertex_order.h): the arrays outgrow the caches. The renumbering costs about ten to twenty
// steps' worth; it saves about two thirds of every step where the file's order scatters the rings,
// and nothing where that order is already local, so it is left out for short smoothings. The
// result is the same to the bit in either order.
inline constexpr size_t kReorderAbove = 200000;
inline constexpr int kReorderSteps = 100;

// laplacian_smooth or chebyshev_smooth, by `scheme`; in breadth-first order above kReorderAbove
// vertices and from kReorderSteps steps (the most any component takes) on.
void smooth_over_rings(const VertexAdjacency& adjacency, const std::vector<uint32_t>& label,
                       const std::vector<int>& iterations, std::vector<double>& values,
                       SmoothingScheme scheme, int threads = 0);
// Four signals at once (each component of the vectors one): the same numbers as four calls, in
// one pass over the rings per step.
void smooth_over_rings(const VertexAdjacency& adjacency, const std::vector<uint32_t>& label,
                       const std::vector<int>& iterations, std::vector<glm::dvec4>& values,
                       SmoothingScheme scheme, int threads = 0);

// Population variance of `values` over {i} ∪ N(i), per vertex.
std::vector<double> one_ring_variance(const VertexAdjacency& adjacency,
                                      const std::vector<double>& values, int threads = 0);

// Mean edge length of each component (each undirected edge counted once).
std::vector<double> component_mean_edge_length(const std::vector<glm::vec3>& positions,
                                               const VertexAdjacency& adjacency,
                                               const Components& components);

}  // namespace countershade
