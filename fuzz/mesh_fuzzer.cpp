// Fuzzes mesh loading (mesh/mesh_io): the first byte picks the format (OBJ, PLY, OFF or STL), the
// rest is the file. Besides a clean refusal of bad files, it holds countershade's own readers to
// their promise: where the OBJ or PLY reader and the fan check vouch for a file, the file check
// accepts it and OpenMesh reads the same vertices and triangles from it.
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "fuzz/fuzz_input.h"
#include "mesh/fan_check.h"
#include "mesh/mesh_file_check.h"
#include "mesh/mesh_io.h"
#include "mesh/obj_reader.h"
#include "mesh/ply_reader.h"

namespace {

using countershade::TriangleMesh;

[[noreturn]] void finding(const char* what) {
  std::fprintf(stderr, "finding: %s\n", what);
  std::abort();
}

// What the reader of `ext` alone makes of the file, or none where it declines.
std::optional<TriangleMesh> read_by_own_reader(const std::filesystem::path& path, bool obj) {
  if (obj) return countershade::read_obj(path);
  const auto soup = countershade::read_ply_soup(path);
  if (!soup) return std::nullopt;
  TriangleMesh mesh;
  mesh.positions = soup->positions;
  mesh.triangles = soup->fan_triangles();
  return mesh;
}

void expect_open_meshs_reading(const std::filesystem::path& path, bool obj) {
  std::optional<TriangleMesh> ours;
  try {
    countershade::check_mesh_file_structure(path, obj ? ".obj" : ".ply");  // refuses first
    ours = read_by_own_reader(path, obj);
  } catch (const countershade::InputError&) {
    return;
  }
  if (!ours || !countershade::forms_one_fan_at_every_vertex(ours->vertex_count(), ours->triangles))
    return;
  OpenMesh::TriMesh_ArrayKernelT<> om;
  if (!OpenMesh::IO::read_mesh(om, path.string())) finding("OpenMesh cannot read a vouched file");
  if (om.n_vertices() != ours->vertex_count() || om.n_faces() != ours->triangle_count())
    finding("OpenMesh reads other counts from a vouched file");
  for (auto vh : om.vertices()) {
    // The same bits (a NaN, which load_mesh then refuses, is not equal to itself).
    const float p[3] = {om.point(vh)[0], om.point(vh)[1], om.point(vh)[2]};
    if (std::memcmp(p, &ours->positions[size_t(vh.idx())], sizeof p) != 0)
      finding("a vertex differs from OpenMesh's");
  }
  for (auto fh : om.faces()) {
    int k = 0;
    for (auto vh : om.fv_range(fh))
      if (unsigned(vh.idx()) != ours->triangles[size_t(fh.idx())][k++])
        finding("a triangle differs from OpenMesh's");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  static const char* const kNames[] = {"mesh.obj", "mesh.ply", "mesh.off", "mesh.stl"};
  const int format = data[0] % 4;
  const auto path = countershade::fuzz::write_input(data + 1, size - 1, kNames[format]);
  if (format <= 1) expect_open_meshs_reading(path, format == 0);
  return countershade::fuzz::expect_clean_refusal([&] { countershade::load_mesh(path); });
}
