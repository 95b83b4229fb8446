#include "mesh/surface_graph.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <numeric>

#include "mesh/smoothing.h"
#include "mesh/triangle_mesh.h"

namespace countershade {
namespace {

double default_tolerance(const std::vector<glm::vec3>& positions) {
  BoundingBox box;
  for (const auto& p : positions) box.extend(p);
  return box.valid() ? 1e-6 * double(box.diagonal()) : 0.0;
}

uint32_t find_root(std::vector<uint32_t>& parent, uint32_t v) {
  while (parent[v] != v) v = parent[v] = parent[parent[v]];
  return v;
}

// Cell coordinates of a point in a grid of cells `cell` wide, as 64-bit integers, clamped so
// that far or non-finite points cannot overflow the conversion (they only share cells then,
// which costs comparisons, not correctness).
glm::i64vec3 cell_of(const glm::dvec3& p, double cell) {
  const glm::dvec3 c = glm::clamp(glm::floor(p / cell), glm::dvec3(-0x1p62), glm::dvec3(0x1p62));
  return glm::i64vec3(std::isnan(c.x) ? 0 : c.x, std::isnan(c.y) ? 0 : c.y,
                      std::isnan(c.z) ? 0 : c.z);
}

// The vertices inserted so far, by grid cell: a flat hash table of chains (head per bucket, next
// per vertex). Cells that share a bucket share a chain; the distance test sorts them out.
class CellTable {
 public:
  explicit CellTable(size_t vertices) : next_(vertices, kNone) {
    size_t buckets = 1;
    while (buckets < 2 * vertices) buckets *= 2;
    head_.assign(buckets, kNone);
  }
  template <typename Visit>
  void for_each_in(const glm::i64vec3& c, const Visit& visit) const {
    for (uint32_t v = head_[bucket(c)]; v != kNone; v = next_[v]) visit(v);
  }
  void insert(const glm::i64vec3& c, uint32_t v) {
    uint32_t& head = head_[bucket(c)];
    next_[v] = head;
    head = v;
  }

 private:
  static constexpr uint32_t kNone = UINT32_MAX;
  size_t bucket(const glm::i64vec3& c) const {
    const uint64_t key =
        (uint64_t(c.x) * 73856093u) ^ (uint64_t(c.y) * 19349663u) ^ (uint64_t(c.z) * 83492791u);
    return size_t((key * 0x9E3779B97F4A7C15ull) >> 20) & (head_.size() - 1);
  }
  std::vector<uint32_t> head_, next_;
};

// Groups of vertices within `tolerance` (transitively), numbered by their lowest vertex. Cells
// are 4·tolerance wide, so the points within tolerance of p lie in the one or two cells per axis
// that hold p − tolerance and p + tolerance: 3.4 cells on average (8 with cells half as wide).
// The distance test decides, so the groups do not depend on the width.
std::vector<uint32_t> weld(const std::vector<glm::vec3>& positions, double tolerance) {
  const size_t n = positions.size();
  std::vector<uint32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0u);
  const double cell = tolerance > 0 ? 4.0 * tolerance : 1.0;
  CellTable table(n);
  for (uint32_t v = 0; v < n; ++v) {
    const glm::dvec3 p(positions[v]);
    // A hair wider than the tolerance, so that rounding in p ± tolerance cannot drop a cell.
    const double reach = tolerance * (1 + 1e-9);
    const glm::i64vec3 lo = cell_of(p - reach, cell), hi = cell_of(p + reach, cell);
    for (int64_t z = lo.z; z <= hi.z; ++z)
      for (int64_t y = lo.y; y <= hi.y; ++y)
        for (int64_t x = lo.x; x <= hi.x; ++x)
          table.for_each_in({x, y, z}, [&](uint32_t w) {
            if (glm::length(glm::dvec3(positions[w]) - p) <= tolerance) {
              const uint32_t a = find_root(parent, w), b = find_root(parent, v);
              parent[std::max(a, b)] = std::min(a, b);
            }
          });
    table.insert(cell_of(p, cell), v);
  }
  for (uint32_t v = 0; v < n; ++v) parent[v] = find_root(parent, v);
  return parent;  // each vertex's lowest-index partner
}

}  // namespace

SurfaceGraph surface_graph(const std::vector<glm::vec3>& positions,
                           const std::vector<std::pair<uint32_t, uint32_t>>& edges,
                           double tolerance) {
  SurfaceGraph g;
  const std::vector<uint32_t> root =
      weld(positions, tolerance < 0 ? default_tolerance(positions) : tolerance);
  g.point_of.assign(positions.size(), 0);
  std::vector<uint32_t> point_of_root(positions.size(), UINT32_MAX);
  for (uint32_t v = 0; v < positions.size(); ++v) {
    if (point_of_root[root[v]] == UINT32_MAX) {
      point_of_root[root[v]] = uint32_t(g.first_vertex.size());
      g.first_vertex.push_back(v);
    }
    g.point_of[v] = point_of_root[root[v]];
  }
  std::vector<std::pair<uint32_t, uint32_t>> point_edges;
  point_edges.reserve(edges.size());
  for (const auto& [a, b] : edges) point_edges.emplace_back(g.point_of[a], g.point_of[b]);
  g.adjacency = adjacency_from_edges(g.point_count(), point_edges);
  g.components = connected_components(g.adjacency);
  measure_edges(g, positions);
  return g;
}

void measure_edges(SurfaceGraph& graph, const std::vector<glm::vec3>& positions) {
  std::vector<glm::vec3> points(graph.point_count());
  for (size_t p = 0; p < points.size(); ++p) points[p] = positions[graph.first_vertex[p]];
  graph.mean_edge_length = component_mean_edge_length(points, graph.adjacency, graph.components);
}

SurfaceGraph surface_graph(const std::vector<glm::vec3>& positions,
                           const std::vector<glm::uvec3>& triangles, double tolerance) {
  std::vector<std::pair<uint32_t, uint32_t>> edges;
  edges.reserve(3 * triangles.size());
  for (const auto& t : triangles)
    for (int c = 0; c < 3; ++c) edges.emplace_back(t[c], t[(c + 1) % 3]);
  return surface_graph(positions, edges, tolerance);
}

std::vector<double> SurfaceGraph::to_points(const std::vector<double>& per_vertex) const {
  if (point_count() == point_of.size()) {  // nothing welded: point p is vertex p
    std::vector<double> out(per_vertex.size());
    for (size_t v = 0; v < out.size(); ++v)
      out[v] = 0.0 + per_vertex[v];  // the sum's bits, -0 included
    return out;
  }
  std::vector<double> sum(point_count(), 0.0), count(point_count(), 0.0);
  for (size_t v = 0; v < per_vertex.size(); ++v) {
    sum[point_of[v]] += per_vertex[v];
    count[point_of[v]] += 1.0;
  }
  for (size_t p = 0; p < sum.size(); ++p) sum[p] = count[p] > 1 ? sum[p] / count[p] : sum[p];
  return sum;
}

std::vector<double> SurfaceGraph::to_vertices(const std::vector<double>& per_point) const {
  if (point_count() == point_of.size()) return per_point;  // nothing welded
  std::vector<double> out(point_of.size());
  for (size_t v = 0; v < out.size(); ++v) out[v] = per_point[point_of[v]];
  return out;
}

std::vector<std::pair<uint32_t, uint32_t>> triangulated_edges(const PolygonSoup& polygons) {
  std::vector<std::pair<uint32_t, uint32_t>> edges;
  edges.reserve(2 * polygons.corners.size());
  for (size_t f = 0; f < polygons.face_count(); ++f) {
    const auto p = polygons.face(f);
    for (size_t i = 0; i < p.size(); ++i) edges.emplace_back(p[i], p[(i + 1) % p.size()]);
    for (size_t i = 2; i + 1 < p.size(); ++i) edges.emplace_back(p[0], p[i]);
  }
  return edges;
}

}  // namespace countershade
