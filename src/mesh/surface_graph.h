#pragma once
// The surface a per-vertex signal is smoothed over. Vertices that share a position (within a
// small tolerance) are one point of the surface: meshes split their vertices along UV and normal
// seams (a PLY exported with texture coordinates, a box with hard edges), and smoothing must
// cross those seams as the surface does. The 1-ring is that of the welded points.

#include <cstdint>
#include <glm/vec3.hpp>
#include <utility>
#include <vector>

#include "mesh/adjacency.h"
#include "mesh/polygon_soup.h"

namespace countershade {

struct SurfaceGraph {
  std::vector<uint32_t> point_of;      // #V: the surface point of each vertex
  std::vector<uint32_t> first_vertex;  // #points: the lowest vertex at each point
  VertexAdjacency adjacency;           // the 1-ring of each point
  Components components;               // connected parts of the surface, per point
  // Per component, the mean length of its edges at the positions the graph was built from (or
  // last measured at: see measure_edges): what a width σ in world units becomes in steps.
  std::vector<double> mean_edge_length;

  size_t point_count() const { return first_vertex.size(); }
  // Per-vertex values to per-point values (the mean of the vertices at a point), and back.
  std::vector<double> to_points(const std::vector<double>& per_vertex) const;
  std::vector<double> to_vertices(const std::vector<double>& per_point) const;
};

// Welds the vertices within `tolerance` of each other (default: 1e-6 of the bounding-box
// diagonal) and builds the 1-ring from the edges (undirected, either orientation).
SurfaceGraph surface_graph(const std::vector<glm::vec3>& positions,
                           const std::vector<std::pair<uint32_t, uint32_t>>& edges,
                           double tolerance = -1);
SurfaceGraph surface_graph(const std::vector<glm::vec3>& positions,
                           const std::vector<glm::uvec3>& triangles, double tolerance = -1);

// Measures the graph's mean edge lengths again at new positions of its vertices (a moved or
// scaled mesh keeps its graph, not its lengths).
void measure_edges(SurfaceGraph& graph, const std::vector<glm::vec3>& positions);

// The edges of a soup's polygons after fan triangulation from their first vertex: each polygon's
// sides and its diagonals (v0, v_i), as a triangulated mesh connects them.
std::vector<std::pair<uint32_t, uint32_t>> triangulated_edges(const PolygonSoup& polygons);

}  // namespace countershade
