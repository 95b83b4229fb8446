// countershade's PLY reader against OpenMesh's, its reference: the same vertices, colours and
// triangles for ASCII, little- and big-endian files, double positions, skipped normals and alpha,
// and polygons; the files it does not read (texture coordinates) go to OpenMesh as before; an
// index out of range is an error naming the face.

#include "mesh/ply_reader.h"

#include <gtest/gtest.h>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "core/error.h"
#include "mesh/mesh_io.h"
#include "test_util.h"

namespace countershade {
namespace {

namespace fs = std::filesystem;

// A square pyramid: a quad base and four triangles, coloured.
const float kPositions[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5f, 0.5f, 0.7f}};
const unsigned char kColours[5][3] = {
    {255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {10, 20, 30}, {200, 100, 50}};
const std::vector<std::vector<int>> kFaces = {
    {3, 2, 1, 0}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};

std::string header(const std::string& format, const std::string& position_type, bool extras) {
  std::string h = "ply\nformat " + format + " 1.0\ncomment made by a test\nelement vertex 5\n";
  for (const char* axis : {"x", "y", "z"}) h += "property " + position_type + " " + axis + "\n";
  if (extras) h += "property float nx\nproperty float ny\nproperty float nz\n";
  h += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  if (extras) h += "property uchar alpha\n";
  return h + "element face 5\nproperty list uchar int vertex_indices\nend_header\n";
}

template <class T>
void put(std::string& out, T value, bool big_endian) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  if (big_endian) std::reverse(raw, raw + sizeof(T));
  out.append(raw, sizeof(T));
}

// The pyramid as a PLY file: `format` ascii, binary_little_endian or binary_big_endian.
std::string pyramid(const std::string& format, bool doubles, bool extras) {
  std::string out = header(format, doubles ? "double" : "float", extras);
  const bool big = format == "binary_big_endian";
  for (int v = 0; v < 5; ++v) {
    if (format == "ascii") {
      for (float p : kPositions[v]) out += std::to_string(p) + " ";
      if (extras) out += "0 0 1 ";
      for (unsigned char c : kColours[v]) out += std::to_string(int(c)) + " ";
      out += extras ? "255\n" : "\n";
      continue;
    }
    for (float p : kPositions[v]) doubles ? put(out, double(p), big) : put(out, p, big);
    if (extras)
      for (float n : {0.0f, 0.0f, 1.0f}) put(out, n, big);
    for (unsigned char c : kColours[v]) put(out, c, big);
    if (extras) put(out, uint8_t(255), big);
  }
  for (const auto& face : kFaces) {
    if (format == "ascii") {
      out += std::to_string(face.size());
      for (int i : face) out += " " + std::to_string(i);
      out += "\n";
      continue;
    }
    put(out, uint8_t(face.size()), big);
    for (int i : face) put(out, int32_t(i), big);
  }
  return out;
}

// What OpenMesh reads of a file, as load_mesh did before it had a reader of its own.
TriangleMesh through_open_mesh(const fs::path& path) {
  OpenMesh::TriMesh_ArrayKernelT<> om;
  om.request_vertex_colors();
  OpenMesh::IO::Options options = OpenMesh::IO::Options::VertexColor;
  EXPECT_TRUE(OpenMesh::IO::read_mesh(om, path.string(), options));
  TriangleMesh mesh;
  for (auto vh : om.vertices()) {
    const auto p = om.point(vh);
    const auto c = om.color(vh);
    mesh.positions.emplace_back(p[0], p[1], p[2]);
    mesh.vertex_colors.emplace_back(c[0] / 255.0f, c[1] / 255.0f, c[2] / 255.0f);
  }
  for (auto fh : om.faces()) {
    glm::uvec3 t;
    int k = 0;
    for (auto vh : om.fv_range(fh)) t[k++] = unsigned(vh.idx());
    mesh.triangles.push_back(t);
  }
  return mesh;
}

TEST(PlyReader, ReadsWhatOpenMeshReadsInEveryFormat) {
  testing::TempDir dir;
  for (const char* format : {"ascii", "binary_little_endian", "binary_big_endian"})
    for (bool doubles : {false, true})
      for (bool extras : {false, true}) {
        const std::string name =
            std::string(format) + (doubles ? "-d" : "-f") + (extras ? "-n" : "");
        const fs::path file =
            testing::write_file(dir / (name + ".ply"), pyramid(format, doubles, extras));
        ASSERT_TRUE(read_ply_soup(file)) << name << ": countershade's reader declined it";
        const TriangleMesh ours = load_mesh(file), reference = through_open_mesh(file);
        EXPECT_EQ(ours.positions, reference.positions) << name;
        EXPECT_EQ(ours.vertex_colors, reference.vertex_colors) << name;
        EXPECT_EQ(ours.triangles, reference.triangles) << name;
        EXPECT_EQ(ours.triangle_count(), 6u) << name;  // the quad as two triangles
      }
}

TEST(PlyReader, DeclinesWhatItDoesNotReadAndRefusesIndicesOutOfRange) {
  testing::TempDir dir;
  std::string uv =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty float u\nproperty float v\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n"
      "0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n3 0 1 2\n";
  const fs::path with_uvs = testing::write_file(dir / "uv.ply", uv);
  EXPECT_FALSE(read_ply_soup(with_uvs));
  const TriangleMesh read = load_mesh(with_uvs);  // by OpenMesh, as before
  EXPECT_EQ(read.vertex_count(), 3u);
  EXPECT_TRUE(read.has_uvs());

  std::string bad = pyramid("ascii", false, false);
  bad.replace(bad.rfind("3 0 4"), 5, "3 0 9");
  const fs::path out_of_range = testing::write_file(dir / "range.ply", bad);
  const std::string message = testing::input_error_of([&] { load_mesh(out_of_range); });
  EXPECT_NE(message.find("range.ply: face 4 has a vertex index out of range"), std::string::npos)
      << message;
}

}  // namespace
}  // namespace countershade
