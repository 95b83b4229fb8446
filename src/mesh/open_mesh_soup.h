#pragma once
// A polygon soup added to an OpenMesh mesh as OpenMesh's own readers add a file: the vertices
// (with their colours) and then the polygons, in the file's order. A triangle mesh triangulates
// each polygon as a fan; a polygon mesh keeps it.

#include <OpenMesh/Core/Mesh/Handles.hh>
#include <cstdint>
#include <vector>

#include "mesh/polygon_soup.h"

namespace countershade {

// Returns the number of triangles the polygons give.
template <class Mesh>
size_t add_soup_to_open_mesh(const PolygonSoup& soup, Mesh& mesh) {
  // Room for everything at once, as OpenMesh's importer makes it (3 edges per vertex): grown face
  // by face, its arrays were copied again and again, and a large mesh spent more time in page
  // faults than in building. At most as many faces as the triangulation gives.
  const size_t vertices = soup.positions.size();
  mesh.reserve(vertices, 3 * vertices, soup.corners.size() - 2 * soup.face_count());
  for (size_t v = 0; v < soup.positions.size(); ++v) {
    const glm::vec3& p = soup.positions[v];
    const auto vh = mesh.add_vertex(typename Mesh::Point(p.x, p.y, p.z));
    if (soup.colours.empty()) continue;
    const glm::u8vec3 c = colour_bytes(soup.colours[v]);
    mesh.set_color(vh, typename Mesh::Color(c.x, c.y, c.z));
  }
  size_t triangles = 0;
  std::vector<OpenMesh::VertexHandle> corners;
  for (size_t f = 0; f < soup.face_count(); ++f) {
    const auto face = soup.face(f);
    corners.clear();
    for (unsigned v : face) corners.push_back(mesh.vertex_handle(int(v)));
    mesh.add_face(corners);
    triangles += face.size() - 2;
  }
  return triangles;
}

}  // namespace countershade
