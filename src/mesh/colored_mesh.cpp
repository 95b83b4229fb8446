#include "mesh/colored_mesh.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <algorithm>
#include <cmath>

#include "core/atomic_file.h"
#include "core/error.h"
#include "mesh/mesh_io.h"
#include "mesh/open_mesh_soup.h"

namespace countershade {

struct ColoredMeshFile::Impl {
  OpenMesh::PolyMesh_ArrayKernelT<> mesh;
};

ColoredMeshFile::ColoredMeshFile(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
ColoredMeshFile::~ColoredMeshFile() = default;
ColoredMeshFile::ColoredMeshFile(ColoredMeshFile&&) noexcept = default;

ColoredMeshFile ColoredMeshFile::read(const std::filesystem::path& path) {
  // The triangle loader applies every validity check (NaN, indices, non-manifold, degenerate),
  // and hands back a PLY file's polygons as listed when its own reader read them.
  std::optional<PolygonSoup> soup;
  TriangleMesh checked = load_mesh(path, &soup);
  if (!checked.has_vertex_colors())
    throw_input_error(path.string(),
                      "mesh has no vertex colours (mesh-usm enhances vertex colours)");
  auto impl = std::make_unique<Impl>();
  impl->mesh.request_vertex_colors();
  if (soup) {
    add_soup_to_open_mesh(*soup, impl->mesh);
    return ColoredMeshFile(std::move(impl));
  }
  OpenMesh::IO::Options options = OpenMesh::IO::Options::VertexColor;
  if (!OpenMesh::IO::read_mesh(impl->mesh, path.string(), options) ||
      !options.check(OpenMesh::IO::Options::VertexColor))
    throw_input_error(path.string(), "cannot read the mesh's vertex colours");
  if (impl->mesh.n_vertices() != checked.vertex_count())
    throw_input_error(path.string(),
                      "vertex count differs between readers; the file may be malformed");
  return ColoredMeshFile(std::move(impl));
}

size_t ColoredMeshFile::vertex_count() const { return impl_->mesh.n_vertices(); }

std::vector<glm::vec3> ColoredMeshFile::positions() const {
  std::vector<glm::vec3> out;
  out.reserve(vertex_count());
  for (auto vh : impl_->mesh.vertices()) {
    auto p = impl_->mesh.point(vh);
    out.emplace_back(p[0], p[1], p[2]);
  }
  return out;
}

std::vector<std::vector<uint32_t>> ColoredMeshFile::polygons() const {
  std::vector<std::vector<uint32_t>> out;
  out.reserve(impl_->mesh.n_faces());
  for (auto fh : impl_->mesh.faces()) {
    out.emplace_back();
    for (auto vh : impl_->mesh.fv_range(fh)) out.back().push_back(uint32_t(vh.idx()));
  }
  return out;
}

std::vector<glm::dvec3> ColoredMeshFile::colors() const {
  std::vector<glm::dvec3> out;
  out.reserve(vertex_count());
  for (auto vh : impl_->mesh.vertices()) {
    auto c = impl_->mesh.color(vh);
    out.emplace_back(c[0] / 255.0, c[1] / 255.0, c[2] / 255.0);
  }
  return out;
}

void ColoredMeshFile::set_colors(const std::vector<glm::dvec3>& colors) {
  size_t i = 0;
  for (auto vh : impl_->mesh.vertices()) {
    OpenMesh::Vec3uc c;
    for (int k = 0; k < 3; ++k)
      c[k] = static_cast<unsigned char>(std::lround(std::clamp(colors[i][k], 0.0, 1.0) * 255.0));
    impl_->mesh.set_color(vh, c);
    ++i;
  }
}

void ColoredMeshFile::write(const std::filesystem::path& path) const {
  write_atomically(path, [&](const std::filesystem::path& temp) {
    OpenMesh::IO::Options options =
        OpenMesh::IO::Options::VertexColor | OpenMesh::IO::Options::Binary;
    if (!OpenMesh::IO::write_mesh(impl_->mesh, temp.string(), options))
      throw std::runtime_error(path.string() + ": cannot write mesh");
  });
}

}  // namespace countershade
