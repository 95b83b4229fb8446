#pragma once
// Vertices and polygons as a file lists them, before OpenMesh builds their connectivity: what
// countershade's own readers (OFF, and the common PLY files) produce.

#include <cstddef>
#include <cstdint>
#include <glm/gtc/type_precision.hpp>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

namespace countershade {

struct PolygonSoup {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> colours;  // per vertex in [0, 1], or empty
  // The faces' vertex indices (counter-clockwise), one face after another; face f is
  // corners[face_ends[f − 1] … face_ends[f]) (from 0 for the first). Flat, so that a mesh of
  // millions of faces is two allocations rather than one per face.
  std::vector<unsigned> corners;
  std::vector<size_t> face_ends;

  size_t face_count() const { return face_ends.size(); }
  std::span<const unsigned> face(size_t f) const {
    const size_t begin = f == 0 ? 0 : face_ends[f - 1];
    return {corners.data() + begin, face_ends[f] - begin};
  }
  void add_face(std::span<const unsigned> indices) {
    corners.insert(corners.end(), indices.begin(), indices.end());
    face_ends.push_back(corners.size());
  }
  // The polygons cut into fans from their first corner, as OpenMesh's triangle mesh cuts them.
  std::vector<glm::uvec3> fan_triangles() const {
    std::vector<glm::uvec3> triangles;
    triangles.reserve(corners.size() - 2 * face_count());
    for (size_t f = 0; f < face_count(); ++f) {
      const auto p = face(f);
      for (size_t k = 1; k + 1 < p.size(); ++k) triangles.emplace_back(p[0], p[k], p[k + 1]);
    }
    return triangles;
  }
};

// A colour in [0, 1] as the byte per channel a mesh stores (rounded to nearest), as OpenMesh
// stores the colours its readers read.
inline glm::u8vec3 colour_bytes(const glm::vec3& colour) {
  const glm::vec3 c = colour * 255.0f + 0.5f;
  return {uint8_t(c.x), uint8_t(c.y), uint8_t(c.z)};
}

}  // namespace countershade
