#pragma once
// CSR 1-ring adjacency: offsets plus concatenated neighbour indices (the CPU analogue of the two
// connectivity textures of Ritschel et al. 2008), and connected components.

#include <cstdint>
#include <glm/vec3.hpp>
#include <span>
#include <utility>
#include <vector>

namespace countershade {

struct VertexAdjacency {
  std::vector<uint32_t> offsets;     // #V+1; neighbours of v are [offsets[v], offsets[v+1])
  std::vector<uint32_t> neighbours;  // sorted ascending within each vertex, no duplicates

  size_t vertex_count() const { return offsets.empty() ? 0 : offsets.size() - 1; }
  std::span<const uint32_t> of(size_t v) const {
    return {neighbours.data() + offsets[v], neighbours.data() + offsets[v + 1]};
  }
};

// From undirected edges (either orientation, duplicates allowed).
VertexAdjacency adjacency_from_edges(size_t vertex_count,
                                     const std::vector<std::pair<uint32_t, uint32_t>>& edges);
// From triangles: the 1-ring of v is every vertex sharing a triangle edge with v.
VertexAdjacency adjacency_from_triangles(size_t vertex_count,
                                         const std::vector<glm::uvec3>& triangles);

// Component label per vertex (0..count-1, numbered in order of the lowest vertex index).
struct Components {
  std::vector<uint32_t> label;
  uint32_t count = 0;
};
Components connected_components(const VertexAdjacency& adjacency);

}  // namespace countershade
