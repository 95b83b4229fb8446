#pragma once
// The renderer's mesh: shared (welded) vertices for connectivity, per-corner attributes for
// shading. Welded vertices matter: surface smoothing runs over vertex connectivity, so a hard edge
// must keep its vertices shared and express the crease only in the per-corner normals.

#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <vector>

namespace countershade {

struct TriangleMesh {
  std::vector<glm::vec3> positions;   // #V vertex positions
  std::vector<glm::uvec3> triangles;  // #F vertex indices, counter-clockwise = front
  std::vector<glm::vec3>
      corner_normals;                 // 3·#F unit shading normals (triangle t, corner c at 3t+c)
  std::vector<glm::vec2> corner_uvs;  // 3·#F texture coordinates, or empty
  std::vector<glm::vec3> vertex_colors;  // #V colours in [0,1] as stored in the file, or empty

  size_t vertex_count() const { return positions.size(); }
  size_t triangle_count() const { return triangles.size(); }
  bool has_uvs() const { return !corner_uvs.empty(); }
  bool has_vertex_colors() const { return !vertex_colors.empty(); }
};

struct BoundingBox {
  glm::vec3 lo{1e30f}, hi{-1e30f};
  void extend(const glm::vec3& p);
  void extend(const BoundingBox& b);
  float diagonal() const;
  bool valid() const { return lo.x <= hi.x; }
};

BoundingBox bounding_box(const TriangleMesh& mesh);

// Fills corner_normals. Corners of faces whose normals differ by more than `crease_angle_deg`
// do not share a normal; 180 gives fully smooth normals. Each corner's normal is the
// angle-weighted mean of the face normals around its vertex within the crease angle.
void compute_corner_normals(TriangleMesh& mesh, double crease_angle_deg);

// The corners (3t + c) incident to each vertex, as CSR: corners of vertex v are
// corners[offsets[v] .. offsets[v+1]).
struct VertexCorners {
  std::vector<uint32_t> offsets, corners;
};
VertexCorners vertex_corners(const TriangleMesh& mesh);

// Applies an affine transform to positions and normals (normals by the inverse transpose).
void transform_mesh(TriangleMesh& mesh, const glm::dmat4& transform);

// Twice the area of triangle t (the length of the edge cross product).
double triangle_double_area(const TriangleMesh& mesh, size_t t);

// Mean edge length over all triangle edges (each shared edge counted once per triangle).
double mean_edge_length(const TriangleMesh& mesh);

}  // namespace countershade
