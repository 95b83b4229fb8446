#pragma once
// A vertex order that keeps neighbours close in memory. Smoothing gathers each vertex's 1-ring
// from the signal; on a mesh whose file order scatters neighbours (subdivided or merged scans),
// most of those reads miss the cache once the arrays outgrow it. Numbering the vertices breadth
// first (Cuthill–McKee without the degree sort) puts each ring within about one wavefront of its
// vertex, a few thousand entries even at 10 million vertices.

#include <cstdint>
#include <vector>

#include "mesh/adjacency.h"

namespace countershade {

// Vertices in breadth-first order: each component from its lowest-index unvisited vertex,
// neighbours in adjacency order. order[new] = old.
std::vector<uint32_t> breadth_first_order(const VertexAdjacency& adjacency);

// The same graph with vertex order[i] renumbered i. Each vertex keeps its neighbours in their
// original sequence (renumbered, so no longer ascending): sums over a ring run in the same order
// and give the same bits as on the original numbering.
VertexAdjacency renumbered(const VertexAdjacency& adjacency, const std::vector<uint32_t>& order);

// values[order[i]] for every i, and the inverse, scattering back.
template <typename T>
std::vector<T> gathered(const std::vector<T>& values, const std::vector<uint32_t>& order) {
  std::vector<T> out(order.size());
  for (size_t i = 0; i < order.size(); ++i) out[i] = values[order[i]];
  return out;
}
template <typename T>
void scatter(const std::vector<T>& reordered, const std::vector<uint32_t>& order,
             std::vector<T>& values) {
  for (size_t i = 0; i < order.size(); ++i) values[order[i]] = reordered[i];
}

}  // namespace countershade
