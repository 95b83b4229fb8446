#include "mesh/adjacency.h"

#include <algorithm>
#include <numeric>

#include "core/parallel.h"

namespace countershade {

VertexAdjacency adjacency_from_edges(size_t vertex_count,
                                     const std::vector<std::pair<uint32_t, uint32_t>>& edges) {
  VertexAdjacency adj;
  adj.offsets.assign(vertex_count + 1, 0);
  for (const auto& [a, b] : edges) {
    if (a == b) continue;
    ++adj.offsets[a + 1];
    ++adj.offsets[b + 1];
  }
  for (size_t v = 0; v < vertex_count; ++v) adj.offsets[v + 1] += adj.offsets[v];
  std::vector<uint32_t> fill(adj.offsets.begin(), adj.offsets.end() - 1);
  std::vector<uint32_t> all(adj.offsets.back());
  for (const auto& [a, b] : edges) {
    if (a == b) continue;
    all[fill[a]++] = b;
    all[fill[b]++] = a;
  }
  // Sort and deduplicate each vertex's list (interior edges appear once per adjacent face), each
  // in place and side by side, then pack them.
  std::vector<uint32_t> offsets(vertex_count + 1, 0);
  parallel_ranges(
      vertex_count, 0,
      [&](size_t first, size_t last) {
        for (size_t v = first; v < last; ++v) {
          auto begin = all.begin() + adj.offsets[v], end = all.begin() + adj.offsets[v + 1];
          std::sort(begin, end);
          offsets[v + 1] = uint32_t(std::unique(begin, end) - begin);
        }
      },
      4096);
  for (size_t v = 0; v < vertex_count; ++v) offsets[v + 1] += offsets[v];
  std::vector<uint32_t> packed(offsets.back());
  parallel_ranges(
      vertex_count, 0,
      [&](size_t first, size_t last) {
        for (size_t v = first; v < last; ++v)
          std::copy_n(all.begin() + adj.offsets[v], offsets[v + 1] - offsets[v],
                      packed.begin() + offsets[v]);
      },
      4096);
  adj.offsets = std::move(offsets);
  adj.neighbours = std::move(packed);
  return adj;
}

VertexAdjacency adjacency_from_triangles(size_t vertex_count,
                                         const std::vector<glm::uvec3>& triangles) {
  std::vector<std::pair<uint32_t, uint32_t>> edges;
  edges.reserve(3 * triangles.size());
  for (const auto& t : triangles)
    for (int c = 0; c < 3; ++c) edges.emplace_back(t[c], t[(c + 1) % 3]);
  return adjacency_from_edges(vertex_count, edges);
}

Components connected_components(const VertexAdjacency& adjacency) {
  const size_t n = adjacency.vertex_count();
  Components result;
  result.label.assign(n, UINT32_MAX);
  std::vector<uint32_t> stack;
  for (size_t seed = 0; seed < n; ++seed) {
    if (result.label[seed] != UINT32_MAX) continue;
    uint32_t id = result.count++;
    result.label[seed] = id;
    stack.push_back(uint32_t(seed));
    while (!stack.empty()) {
      uint32_t v = stack.back();
      stack.pop_back();
      for (uint32_t w : adjacency.of(v))
        if (result.label[w] == UINT32_MAX) {
          result.label[w] = id;
          stack.push_back(w);
        }
    }
  }
  return result;
}

}  // namespace countershade
