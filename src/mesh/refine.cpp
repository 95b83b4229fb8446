#include "mesh/refine.h"

#include <cmath>
#include <glm/geometric.hpp>
#include <queue>
#include <stdexcept>
#include <unordered_map>

namespace countershade {
namespace {

uint64_t edge_key(uint32_t a, uint32_t b) {
  if (a > b) std::swap(a, b);
  return (uint64_t(a) << 32) | b;
}

// Splits the longest edge first until none is longer than the limit. Each split puts a vertex at
// the edge's midpoint and halves both triangles that share the edge.
class EdgeSplitter {
 public:
  EdgeSplitter(TriangleMesh& mesh, double max_length, std::vector<float>* vertex_values)
      : mesh_(mesh), max_length_(max_length), vertex_values_(vertex_values) {
    for (uint32_t t = 0; t < mesh.triangles.size(); ++t)
      for (int c = 0; c < 3; ++c) add_edge(mesh.triangles[t][c], mesh.triangles[t][(c + 1) % 3], t);
  }

  size_t run() {
    size_t splits = 0;
    while (!queue_.empty()) {
      const uint64_t key = queue_.top().second;
      queue_.pop();
      auto found = edge_triangles_.find(key);
      if (found == edge_triangles_.end()) continue;  // a stale entry: the edge was split already
      const std::vector<uint32_t> triangles = std::move(found->second);
      edge_triangles_.erase(found);
      const uint32_t a = uint32_t(key >> 32), b = uint32_t(key & 0xffffffffu);
      const uint32_t m = midpoint_vertex(a, b);
      for (uint32_t t : triangles) split_triangle(t, a, b, m);
      ++splits;
    }
    return splits;
  }

 private:
  double length(uint32_t a, uint32_t b) const {
    return glm::length(glm::dvec3(mesh_.positions[a]) - glm::dvec3(mesh_.positions[b]));
  }

  void add_edge(uint32_t a, uint32_t b, uint32_t t) {
    auto& list = edge_triangles_[edge_key(a, b)];
    if (list.empty() && length(a, b) > max_length_) queue_.emplace(length(a, b), edge_key(a, b));
    list.push_back(t);
  }

  uint32_t midpoint_vertex(uint32_t a, uint32_t b) {
    const uint32_t m = uint32_t(mesh_.positions.size());
    mesh_.positions.push_back(0.5f * (mesh_.positions[a] + mesh_.positions[b]));
    if (mesh_.has_vertex_colors())
      mesh_.vertex_colors.push_back(0.5f * (mesh_.vertex_colors[a] + mesh_.vertex_colors[b]));
    if (vertex_values_)
      vertex_values_->push_back(0.5f * ((*vertex_values_)[a] + (*vertex_values_)[b]));
    return m;
  }

  // Triangle t's corners (first, second, opposite) become t = (first, m, opposite) and a new
  // triangle u = (m, second, opposite); per-corner attributes are split alike.
  template <class Corners>
  static void split_corners(Corners& corners, uint32_t t, int first, int second, int opposite) {
    auto cp = corners[3 * t + first], cq = corners[3 * t + second], co = corners[3 * t + opposite];
    auto cm = 0.5f * (cp + cq);
    corners[3 * t] = cp;
    corners[3 * t + 1] = cm;
    corners[3 * t + 2] = co;
    corners.push_back(cm);
    corners.push_back(cq);
    corners.push_back(co);
  }

  void split_triangle(uint32_t t, uint32_t a, uint32_t b, uint32_t m) {
    const glm::uvec3 tri = mesh_.triangles[t];
    // Rotate so that the split edge is corners first -> second (either direction) and the third is
    // opposite.
    const int ca = tri.x == a ? 0 : tri.y == a ? 1 : 2, cb = tri.x == b ? 0 : tri.y == b ? 1 : 2;
    const int first = (ca + 1) % 3 == cb ? ca : cb;
    const int second = (first + 1) % 3, opposite = (first + 2) % 3;
    const uint32_t p = tri[first], q = tri[second], o = tri[opposite];
    const uint32_t u = uint32_t(mesh_.triangles.size());
    mesh_.triangles[t] = {p, m, o};  // both keep the original winding
    mesh_.triangles.push_back({m, q, o});
    if (!mesh_.corner_normals.empty()) {
      split_corners(mesh_.corner_normals, t, first, second, opposite);
      mesh_.corner_normals[3 * t + 1] = glm::normalize(mesh_.corner_normals[3 * t + 1]);
      mesh_.corner_normals[3 * u] = glm::normalize(mesh_.corner_normals[3 * u]);
    }
    if (mesh_.has_uvs()) split_corners(mesh_.corner_uvs, t, first, second, opposite);
    for (auto& owner : edge_triangles_[edge_key(q, o)])  // edge (q, o) now belongs to u
      if (owner == t) owner = u;
    add_edge(p, m, t);
    add_edge(m, o, t);
    add_edge(m, q, u);
    add_edge(m, o, u);
  }

  TriangleMesh& mesh_;
  double max_length_;
  std::vector<float>* vertex_values_;
  std::unordered_map<uint64_t, std::vector<uint32_t>>
      edge_triangles_;                                      // 1 triangle on a boundary, 2 inside
  std::priority_queue<std::pair<double, uint64_t>> queue_;  // longest first
};

}  // namespace

size_t refine_long_edges(TriangleMesh& mesh, double max_length, std::vector<float>* vertex_values) {
  if (!(max_length > 0))
    throw std::invalid_argument("refine_long_edges: max_length must be positive");
  return EdgeSplitter(mesh, max_length, vertex_values).run();
}

}  // namespace countershade
