#pragma once
// The baseline of the smoothing comparison: the face-scatter 1-ring average of vcglib's
// VertexColorLaplacian (tri::Smooth), written here from its description because vcglib is not
// packaged in Debian. Per step: clear a per-vertex sum of the four 8-bit channels and a count;
// for each face and each of its edges not on the border, add each end's colour to the other
// end's sum; clear the sums of the border vertices and redo them from the border edges only;
// divide. Serial, on vertex records laid out like a usual vcglib vertex (position, normal,
// colour, flags) and faces holding their vertices and border flags.

#include <cstdint>
#include <glm/vec3.hpp>
#include <map>
#include <utility>
#include <vector>

#include "mesh/triangle_mesh.h"

namespace countershade::bench {

struct FaceScatterMesh {
  struct Vertex {
    float position[3], normal[3];
    uint8_t color[4];
    int flags;
  };
  struct Face {
    uint32_t v[3];
    int border;  // bit j: edge (v[j], v[j+1]) has no other face
  };
  std::vector<Vertex> vertices;
  std::vector<Face> faces;
};

inline FaceScatterMesh face_scatter_mesh(const TriangleMesh& mesh,
                                         const std::vector<uint8_t>& grey) {
  FaceScatterMesh m;
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    m.vertices.push_back({{mesh.positions[v].x, mesh.positions[v].y, mesh.positions[v].z},
                          {0, 0, 1},
                          {grey[v], grey[v], grey[v], 255},
                          0});
  std::map<std::pair<uint32_t, uint32_t>, int> uses;
  const auto key = [](uint32_t a, uint32_t b) {
    return a < b ? std::make_pair(a, b) : std::make_pair(b, a);
  };
  for (const glm::uvec3& t : mesh.triangles)
    for (int j = 0; j < 3; ++j) ++uses[key(t[j], t[(j + 1) % 3])];
  for (const glm::uvec3& t : mesh.triangles) {
    FaceScatterMesh::Face f{{t.x, t.y, t.z}, 0};
    for (int j = 0; j < 3; ++j) f.border |= uses[key(t[j], t[(j + 1) % 3])] == 1 ? 1 << j : 0;
    m.faces.push_back(f);
  }
  return m;
}

inline void face_scatter_smooth(FaceScatterMesh& m, int steps) {
  struct Sum {
    unsigned channel[4];
    int count;
  };
  std::vector<Sum> sum(m.vertices.size());
  const auto add = [&](uint32_t to, uint32_t from) {
    for (int c = 0; c < 4; ++c) sum[to].channel[c] += m.vertices[from].color[c];
    ++sum[to].count;
  };
  const auto each_edge = [&](bool border, auto&& f) {
    for (const FaceScatterMesh::Face& face : m.faces)
      for (int j = 0; j < 3; ++j)
        if (bool(face.border & (1 << j)) == border) f(face.v[j], face.v[(j + 1) % 3]);
  };
  for (int s = 0; s < steps; ++s) {
    std::fill(sum.begin(), sum.end(), Sum{});
    each_edge(false, [&](uint32_t a, uint32_t b) { add(a, b), add(b, a); });
    each_edge(true, [&](uint32_t a, uint32_t b) { sum[a] = sum[b] = Sum{}; });
    each_edge(true, [&](uint32_t a, uint32_t b) { add(a, b), add(b, a); });
    for (size_t v = 0; v < m.vertices.size(); ++v)
      if (sum[v].count > 0)
        for (int c = 0; c < 4; ++c)
          m.vertices[v].color[c] = uint8_t(sum[v].channel[c] / unsigned(sum[v].count));
  }
}

}  // namespace countershade::bench
