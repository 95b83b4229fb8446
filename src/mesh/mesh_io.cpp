#include "mesh/mesh_io.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <mutex>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "mesh/fan_check.h"
#include "mesh/mesh_file_check.h"
#include "mesh/obj_reader.h"
#include "mesh/off_reader.h"
#include "mesh/open_mesh_soup.h"
#include "mesh/ply_check.h"
#include "mesh/ply_reader.h"

namespace countershade {
namespace {

using OMesh = OpenMesh::TriMesh_ArrayKernelT<>;

}  // namespace

void validate_mesh(const TriangleMesh& mesh, const std::string& where) {
  if (mesh.triangles.empty()) throw_input_error(where, "mesh has no faces");
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const auto& p = mesh.positions[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw_input_error(where, "vertex " + std::to_string(v) + " has a NaN or infinite coordinate");
  }
  const size_t nv = mesh.positions.size();
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    if (tri.x >= nv || tri.y >= nv || tri.z >= nv)
      throw_input_error(where,
                        "triangle " + std::to_string(t) + " has a vertex index out of range");
    if (tri.x == tri.y || tri.y == tri.z || tri.x == tri.z || triangle_double_area(mesh, t) == 0.0)
      throw_input_error(where, "triangle " + std::to_string(t) + " is degenerate (zero area)");
  }
}

namespace {

// The file exists, is not empty and has a format we read; returns the lower-case extension.
std::string check_mesh_file(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw_input_error(path.string(), "no such mesh file");
  if (fs::file_size(path, ec) == 0) throw_input_error(path.string(), "mesh file is empty");
  std::string ext = lower_extension(path);
  if (ext != ".obj" && ext != ".ply" && ext != ".off" && ext != ".stl")
    throw_input_error(path.string(),
                      "unsupported mesh format '" + ext + "' (use OBJ, PLY, OFF or STL)");
  return ext;
}

// Runs `read` with OpenMesh's error stream captured and returns what it wrote there.
template <typename Read>
std::string capture_open_mesh_errors(Read&& read) {
  // OpenMesh reports dropped faces (complex edges, non-manifold vertices) only on its error
  // stream; capture it so they become an error rather than a silently incomplete mesh. The
  // capture is connected once: OpenMesh allocates on every connect() and never frees on
  // disconnect(). Intentionally never destroyed, since OpenMesh keeps a pointer to it.
  static std::mutex omerr_mutex;
  static std::ostringstream* reader_log = [] {
    auto* log = new std::ostringstream;
    omerr().disconnect(std::cerr);
    omerr().connect(*log);
    omlog().disable();
    return log;
  }();
  std::lock_guard<std::mutex> lock(omerr_mutex);
  reader_log->str("");
  reader_log->clear();
  read();
  return reader_log->str();
}

// The soup added to `om` (which triangulates polygons); returns the number of triangles they
// should give.
size_t add_polygons(const PolygonSoup& soup, OMesh& om, OpenMesh::IO::Options& options) {
  options = soup.colours.empty() ? OpenMesh::IO::Options()
                                 : OpenMesh::IO::Options(OpenMesh::IO::Options::VertexColor);
  return add_soup_to_open_mesh(soup, om);
}

// The file as countershade's own readers read it: OFF always, PLY when its reader takes the file
// (after the header's check, which keeps a forged count from allocating); else none.
std::optional<PolygonSoup> read_soup(const std::filesystem::path& path, const std::string& ext) {
  if (ext == ".off") return read_off(path);
  if (ext != ".ply") return std::nullopt;
  check_ply(path, PlyCheck::header);
  return read_ply_soup(path);
}

// The file (or the soup read from it) read into `om` by OpenMesh; returns OpenMesh's error output
// and, for a soup and for OBJ, the number of triangles the file describes (else 0).
std::string read_into_open_mesh(const std::filesystem::path& path, const std::string& ext,
                                const PolygonSoup* soup, OMesh& om, OpenMesh::IO::Options& options,
                                size_t& expected_triangles) {
  if (soup)
    return capture_open_mesh_errors([&] { expected_triangles = add_polygons(*soup, om, options); });
  expected_triangles = check_mesh_file_structure(path, ext);
  return capture_open_mesh_errors([&] {
    if (!OpenMesh::IO::read_mesh(om, path.string(), options))
      throw_input_error(path.string(), "cannot read mesh (malformed or unsupported file)");
  });
}

// Positions, colours, and per-corner UVs (from the face's halfedges, else the vertices).
TriangleMesh to_triangle_mesh(OMesh& om, const OpenMesh::IO::Options& options) {
  TriangleMesh mesh;
  mesh.positions.reserve(om.n_vertices());
  for (auto vh : om.vertices()) {
    auto p = om.point(vh);
    mesh.positions.emplace_back(p[0], p[1], p[2]);
  }
  if (options.check(OpenMesh::IO::Options::VertexColor))
    for (auto vh : om.vertices()) {
      auto c = om.color(vh);
      mesh.vertex_colors.emplace_back(c[0] / 255.0f, c[1] / 255.0f, c[2] / 255.0f);
    }
  const bool face_uvs = options.check(OpenMesh::IO::Options::FaceTexCoord);
  const bool vertex_uvs = options.check(OpenMesh::IO::Options::VertexTexCoord);
  mesh.triangles.reserve(om.n_faces());
  for (auto fh : om.faces()) {
    glm::uvec3 tri;
    int c = 0;
    for (auto heh : om.fh_range(fh)) {
      auto vh = om.to_vertex_handle(heh);
      tri[c] = unsigned(vh.idx());
      if (face_uvs || vertex_uvs) {
        auto uv = face_uvs ? om.texcoord2D(heh) : om.texcoord2D(vh);
        mesh.corner_uvs.emplace_back(uv[0], uv[1]);
      }
      if (++c == 3) break;
    }
    mesh.triangles.push_back(tri);
  }
  return mesh;
}

// The soup's polygons as fans from their first corner and its colours through bytes, as OpenMesh
// adds them.
TriangleMesh triangulated(const PolygonSoup& soup) {
  TriangleMesh mesh;
  mesh.positions = soup.positions;
  mesh.vertex_colors.reserve(soup.colours.size());
  for (const glm::vec3& c : soup.colours)
    mesh.vertex_colors.push_back(glm::vec3(colour_bytes(c)) / 255.0f);
  mesh.triangles = soup.fan_triangles();
  return mesh;
}

// The mesh as OpenMesh builds it, refusing the faces it cannot add.
TriangleMesh load_through_open_mesh(const std::filesystem::path& path, const std::string& ext,
                                    const PolygonSoup* soup) {
  OMesh om;
  om.request_vertex_colors();
  om.request_vertex_texcoords2D();
  om.request_halfedge_texcoords2D();
  OpenMesh::IO::Options options = OpenMesh::IO::Options::VertexColor |
                                  OpenMesh::IO::Options::VertexTexCoord |
                                  OpenMesh::IO::Options::FaceTexCoord;
  size_t expected_triangles = 0;
  const std::string log = read_into_open_mesh(path, ext, soup, om, options, expected_triangles);
  if (log.find("complex") != std::string::npos || log.find("non-manifold") != std::string::npos ||
      log.find("failed") != std::string::npos ||
      (expected_triangles > 0 && om.n_faces() < expected_triangles))
    throw_input_error(
        path.string(),
        "mesh is non-manifold: some faces could not be added (complex edge or vertex)");
  return to_triangle_mesh(om, options);
}

}  // namespace

TriangleMesh load_mesh(const std::filesystem::path& path, std::optional<PolygonSoup>* soup_out) {
  const std::string ext = check_mesh_file(path);
  std::optional<PolygonSoup> soup = read_soup(path, ext);
  std::optional<TriangleMesh> mesh = soup            ? triangulated(*soup)
                                     : ext == ".obj" ? read_obj(path)
                                                     : std::nullopt;
  // A surface whose every vertex has one fan needs no half-edge structure to vouch for it: OpenMesh
  // would add every face and give these triangles (tests/mesh/fan_check_test.cpp).
  if (!mesh || !forms_one_fan_at_every_vertex(mesh->vertex_count(), mesh->triangles))
    mesh = load_through_open_mesh(path, ext, soup ? &*soup : nullptr);
  validate_mesh(*mesh, path.string());
  if (soup_out) *soup_out = std::move(soup);
  return std::move(*mesh);
}

}  // namespace countershade
