#pragma once
// Cuts every triangle into K² (each edge into K parts), new vertices appended after the input's
// as subdivision tools do (edge points by edge, then each face's interior points): the large
// meshes of the smoothing measurements (bench/subdivide_mesh.cpp, BM_SmoothLocality).

#include <cstdint>
#include <glm/geometric.hpp>
#include <map>
#include <utility>
#include <vector>

#include "mesh/triangle_mesh.h"

namespace countershade::bench {

struct Subdivided {
  std::vector<glm::vec3> positions;
  std::vector<glm::uvec3> triangles;
};

// The K−1 interior points of edge (a, b), from a to b, appended once per undirected edge.
class EdgePoints {
 public:
  EdgePoints(Subdivided& out, int k) : out_(out), k_(k) {}
  // Vertex index of the point i/K of the way from a to b (0 < i < K).
  uint32_t at(uint32_t a, uint32_t b, int i) {
    const bool flipped = a > b;
    const auto key = flipped ? std::make_pair(b, a) : std::make_pair(a, b);
    auto [it, fresh] = first_.try_emplace(key, uint32_t(out_.positions.size()));
    if (fresh)
      for (int j = 1; j < k_; ++j)
        out_.positions.push_back(
            glm::mix(out_.positions[key.first], out_.positions[key.second], float(j) / float(k_)));
    return it->second + uint32_t((flipped ? k_ - i : i) - 1);
  }

 private:
  Subdivided& out_;
  int k_;
  std::map<std::pair<uint32_t, uint32_t>, uint32_t> first_;
};

// Cuts triangle (a, b, c) into K² on the barycentric grid (i steps towards b, j towards c).
inline void subdivide_triangle(const glm::uvec3& t, int k, EdgePoints& edges, Subdivided& out) {
  std::vector<uint32_t> grid(size_t((k + 1) * (k + 1)));
  const auto id = [&](int i, int j) -> uint32_t& { return grid[size_t(i * (k + 1) + j)]; };
  for (int i = 0; i <= k; ++i)
    for (int j = 0; i + j <= k; ++j) {
      const int l = k - i - j;
      if (i == 0 && j == 0)
        id(i, j) = t.x;
      else if (i == k)
        id(i, j) = t.y;
      else if (j == k)
        id(i, j) = t.z;
      else if (j == 0)
        id(i, j) = edges.at(t.x, t.y, i);
      else if (i == 0)
        id(i, j) = edges.at(t.x, t.z, j);
      else if (l == 0)
        id(i, j) = edges.at(t.y, t.z, j);
      else {
        id(i, j) = uint32_t(out.positions.size());
        out.positions.push_back((float(l) * out.positions[t.x] + float(i) * out.positions[t.y] +
                                 float(j) * out.positions[t.z]) /
                                float(k));
      }
    }
  for (int i = 0; i < k; ++i)
    for (int j = 0; i + j < k; ++j) {
      out.triangles.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
      if (i + j + 1 < k) out.triangles.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
    }
}

inline Subdivided subdivide(const TriangleMesh& in, int k) {
  Subdivided out{in.positions, {}};
  out.triangles.reserve(in.triangles.size() * size_t(k * k));
  EdgePoints edges(out, k);
  for (const glm::uvec3& t : in.triangles) subdivide_triangle(t, k, edges, out);
  return out;
}

}  // namespace countershade::bench
