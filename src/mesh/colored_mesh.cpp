#include "mesh/colored_mesh.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "mesh/mesh_io.h"

namespace countershade {

// The mesh as listed, its colours kept as the bytes' values (colour_bytes gives the bytes back).
struct ColoredMeshFile::Impl {
  PolygonSoup soup;
};

ColoredMeshFile::ColoredMeshFile(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
ColoredMeshFile::~ColoredMeshFile() = default;
ColoredMeshFile::ColoredMeshFile(ColoredMeshFile&&) noexcept = default;

namespace {

// A file countershade's own readers do not read (OBJ), as OpenMesh lists its polygons.
PolygonSoup read_through_open_mesh(const std::filesystem::path& path, size_t vertex_count) {
  OpenMesh::PolyMesh_ArrayKernelT<> mesh;
  mesh.request_vertex_colors();
  OpenMesh::IO::Options options = OpenMesh::IO::Options::VertexColor;
  if (!OpenMesh::IO::read_mesh(mesh, path.string(), options) ||
      !options.check(OpenMesh::IO::Options::VertexColor))
    throw_input_error(path.string(), "cannot read the mesh's vertex colours");
  if (mesh.n_vertices() != vertex_count)
    throw_input_error(path.string(),
                      "vertex count differs between readers; the file may be malformed");
  PolygonSoup soup;
  for (auto vh : mesh.vertices()) {
    const auto p = mesh.point(vh);
    const auto c = mesh.color(vh);
    soup.positions.emplace_back(p[0], p[1], p[2]);
    soup.colours.push_back(glm::vec3(c[0], c[1], c[2]) / 255.0f);
  }
  std::vector<unsigned> face;
  for (auto fh : mesh.faces()) {
    face.clear();
    for (auto vh : mesh.fv_range(fh)) face.push_back(unsigned(vh.idx()));
    soup.add_face(face);
  }
  return soup;
}

}  // namespace

ColoredMeshFile ColoredMeshFile::read(const std::filesystem::path& path) {
  // The triangle loader applies every validity check (NaN, indices, non-manifold, degenerate),
  // and hands back an OFF or PLY file's polygons as listed when its own readers read them.
  std::optional<PolygonSoup> soup;
  TriangleMesh checked = load_mesh(path, &soup);
  if (!checked.has_vertex_colors())
    throw_input_error(path.string(),
                      "mesh has no vertex colours (mesh-usm enhances vertex colours)");
  auto impl = std::make_unique<Impl>();
  impl->soup = soup ? std::move(*soup) : read_through_open_mesh(path, checked.vertex_count());
  for (glm::vec3& c : impl->soup.colours) c = glm::vec3(colour_bytes(c)) / 255.0f;
  return ColoredMeshFile(std::move(impl));
}

size_t ColoredMeshFile::vertex_count() const { return impl_->soup.positions.size(); }

std::vector<glm::vec3> ColoredMeshFile::positions() const { return impl_->soup.positions; }

const PolygonSoup& ColoredMeshFile::polygons() const { return impl_->soup; }

std::vector<glm::dvec3> ColoredMeshFile::colors() const {
  std::vector<glm::dvec3> out;
  out.reserve(vertex_count());
  for (const glm::vec3& c : impl_->soup.colours) out.push_back(glm::dvec3(colour_bytes(c)) / 255.0);
  return out;
}

void ColoredMeshFile::set_colors(const std::vector<glm::dvec3>& colors) {
  for (size_t v = 0; v < vertex_count(); ++v)
    for (int k = 0; k < 3; ++k)
      impl_->soup.colours[v][k] =
          float(std::lround(std::clamp(colors[v][k], 0.0, 1.0) * 255.0)) / 255.0f;
}

void ColoredMeshFile::write(const std::filesystem::path& path, PlyEncoding encoding) const {
  write_ply(path, impl_->soup, encoding);
}

}  // namespace countershade
