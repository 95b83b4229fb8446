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

namespace countershade {
namespace {

using OMesh = OpenMesh::TriMesh_ArrayKernelT<>;

// OpenMesh's OBJ reader skips vertices it cannot parse and faces with bad indices, printing only
// a warning; check the file first so such meshes are errors with a line number. Returns the
// number of triangles the file describes after fan triangulation.
size_t check_obj(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line;
  long long vertices = 0, texcoords = 0;
  size_t line_number = 0, triangles = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.size() < 2) continue;
    if (line[0] == 'v' && line[1] == ' ') {
      ++vertices;
      const char* cursor = line.c_str() + 2;
      for (int k = 0; k < 3; ++k) {
        char* end = nullptr;
        double value = std::strtod(cursor, &end);
        if (end == cursor)
          throw_input_error(path.string() + ": line " + std::to_string(line_number),
                            "vertex " + std::to_string(vertices - 1) + " has fewer than 3 coordinates");
        if (!std::isfinite(value))
          throw_input_error(path.string() + ": line " + std::to_string(line_number),
                            "vertex " + std::to_string(vertices - 1) + " has a NaN or infinite coordinate");
        cursor = end;
      }
    } else if (line[0] == 'v' && line[1] == 't') {
      ++texcoords;
    } else if (line[0] == 'f' && line[1] == ' ') {
      std::istringstream fields(line.substr(2));
      std::string corner;
      int count = 0;
      std::vector<long long> face;
      while (fields >> corner) {
        ++count;
        long long index[2] = {0, 0};
        size_t start = 0;
        for (int k = 0; k < 2 && start <= corner.size(); ++k) {
          size_t end = corner.find('/', start);
          std::string part = corner.substr(start, end == std::string::npos ? end : end - start);
          if (!part.empty()) {
            try {
              index[k] = std::stoll(part);
            } catch (...) {
              throw_input_error(path.string() + ": line " + std::to_string(line_number),
                                "face index '" + part + "' is not a number");
            }
          }
          if (end == std::string::npos) break;
          start = end + 1;
        }
        long long limits[2] = {vertices, texcoords};
        const char* names[2] = {"vertex", "texture coordinate"};
        for (int k = 0; k < 2; ++k) {
          long long i = index[k];
          if (k == 1 && i == 0) continue;  // no texture coordinate given
          long long resolved = i < 0 ? limits[k] + i + 1 : i;
          if (i == 0 || resolved < 1 || resolved > limits[k])
            throw_input_error(path.string() + ": line " + std::to_string(line_number),
                              std::string("face ") + names[k] + " index " + std::to_string(i) +
                                  " is out of range (1.." + std::to_string(limits[k]) + ")");
          if (k == 0) face.push_back(resolved);
        }
      }
      std::sort(face.begin(), face.end());
      if (std::adjacent_find(face.begin(), face.end()) != face.end())
        throw_input_error(path.string() + ": line " + std::to_string(line_number),
                          "face is degenerate (a vertex appears twice)");
      triangles += size_t(std::max(0, count - 2));
      if (count < 3)
        throw_input_error(path.string() + ": line " + std::to_string(line_number),
                          "face has fewer than 3 vertices");
    }
  }
  return triangles;
}

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
      throw_input_error(where, "triangle " + std::to_string(t) + " has a vertex index out of range");
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
    throw_input_error(path.string(), "unsupported mesh format '" + ext + "' (use OBJ, PLY, OFF or STL)");
  return ext;
}

// Reads through OpenMesh and returns what it wrote to its error stream.
std::string read_open_mesh(const std::filesystem::path& path, OMesh& om, OpenMesh::IO::Options& options) {
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
  if (!OpenMesh::IO::read_mesh(om, path.string(), options))
    throw_input_error(path.string(), "cannot read mesh (malformed or unsupported file)");
  return reader_log->str();
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

}  // namespace

TriangleMesh load_mesh(const std::filesystem::path& path) {
  const std::string ext = check_mesh_file(path);
  const size_t expected_triangles = ext == ".obj" ? check_obj(path) : 0;
  OMesh om;
  om.request_vertex_colors();
  om.request_vertex_texcoords2D();
  om.request_halfedge_texcoords2D();
  OpenMesh::IO::Options options = OpenMesh::IO::Options::VertexColor | OpenMesh::IO::Options::VertexTexCoord |
                                  OpenMesh::IO::Options::FaceTexCoord;
  const std::string log = read_open_mesh(path, om, options);
  if (log.find("complex") != std::string::npos || log.find("non-manifold") != std::string::npos ||
      log.find("failed") != std::string::npos || (expected_triangles > 0 && om.n_faces() < expected_triangles))
    throw_input_error(path.string(), "mesh is non-manifold: some faces could not be added (complex edge or vertex)");
  TriangleMesh mesh = to_triangle_mesh(om, options);
  validate_mesh(mesh, path.string());
  return mesh;
}

}  // namespace countershade
