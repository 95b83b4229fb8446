#include "mesh/refine.h"

#include <cmath>
#include <queue>
#include <stdexcept>
#include <unordered_map>

#include <glm/geometric.hpp>

namespace countershade {
namespace {

uint64_t edge_key(uint32_t a, uint32_t b) {
  if (a > b) std::swap(a, b);
  return (uint64_t(a) << 32) | b;
}

}  // namespace

size_t refine_long_edges(TriangleMesh& mesh, double max_length, std::vector<float>* vertex_values) {
  if (!(max_length > 0)) throw std::invalid_argument("refine_long_edges: max_length must be positive");
  // Edge -> triangles that use it (1 on a boundary, 2 inside).
  std::unordered_map<uint64_t, std::vector<uint32_t>> edge_triangles;
  auto length = [&](uint32_t a, uint32_t b) {
    return glm::length(glm::dvec3(mesh.positions[a]) - glm::dvec3(mesh.positions[b]));
  };
  using Entry = std::pair<double, uint64_t>;
  std::priority_queue<Entry> queue;  // longest first; stale entries are skipped when popped
  auto add_edge = [&](uint32_t a, uint32_t b, uint32_t t) {
    auto& list = edge_triangles[edge_key(a, b)];
    if (list.empty() && length(a, b) > max_length) queue.emplace(length(a, b), edge_key(a, b));
    list.push_back(t);
  };
  for (uint32_t t = 0; t < mesh.triangles.size(); ++t)
    for (int c = 0; c < 3; ++c) add_edge(mesh.triangles[t][c], mesh.triangles[t][(c + 1) % 3], t);

  const bool uvs = mesh.has_uvs(), normals = !mesh.corner_normals.empty(), colors = mesh.has_vertex_colors();
  size_t splits = 0;
  while (!queue.empty()) {
    uint64_t key = queue.top().second;
    queue.pop();
    auto found = edge_triangles.find(key);
    if (found == edge_triangles.end()) continue;
    std::vector<uint32_t> triangles = std::move(found->second);
    edge_triangles.erase(found);
    uint32_t a = uint32_t(key >> 32), b = uint32_t(key & 0xffffffffu);

    uint32_t m = uint32_t(mesh.positions.size());
    mesh.positions.push_back(0.5f * (mesh.positions[a] + mesh.positions[b]));
    if (colors) mesh.vertex_colors.push_back(0.5f * (mesh.vertex_colors[a] + mesh.vertex_colors[b]));
    if (vertex_values) vertex_values->push_back(0.5f * ((*vertex_values)[a] + (*vertex_values)[b]));

    for (uint32_t t : triangles) {
      glm::uvec3 tri = mesh.triangles[t];
      // Rotate so that the split edge is corners 0 -> 1 (either direction) and corner 2 is opposite.
      int ca = tri.x == a ? 0 : tri.y == a ? 1 : 2, cb = tri.x == b ? 0 : tri.y == b ? 1 : 2;
      int first = (ca + 1) % 3 == cb ? ca : cb;  // the edge runs first -> first+1
      int second = (first + 1) % 3, opposite = (first + 2) % 3;
      uint32_t p = tri[first], q = tri[second], o = tri[opposite];
      uint32_t u = uint32_t(mesh.triangles.size());
      // t becomes (p, m, o); the new triangle u is (m, q, o): both keep the original winding.
      mesh.triangles[t] = {p, m, o};
      mesh.triangles.push_back({m, q, o});
      auto split_corners = [&](auto& corners) {
        auto cp = corners[3 * t + first], cq = corners[3 * t + second], co = corners[3 * t + opposite];
        auto cm = 0.5f * (cp + cq);
        corners[3 * t] = cp;
        corners[3 * t + 1] = cm;
        corners[3 * t + 2] = co;
        corners.push_back(cm);
        corners.push_back(cq);
        corners.push_back(co);
      };
      if (normals) {
        split_corners(mesh.corner_normals);
        mesh.corner_normals[3 * t + 1] = glm::normalize(mesh.corner_normals[3 * t + 1]);
        mesh.corner_normals[3 * u] = glm::normalize(mesh.corner_normals[3 * u]);
      }
      if (uvs) split_corners(mesh.corner_uvs);
      // Edge (q, o) now belongs to u instead of t.
      for (auto& owner : edge_triangles[edge_key(q, o)])
        if (owner == t) owner = u;
      add_edge(p, m, t);
      add_edge(m, o, t);
      add_edge(m, q, u);
      add_edge(m, o, u);
    }
    ++splits;
  }
  return splits;
}

}  // namespace countershade
