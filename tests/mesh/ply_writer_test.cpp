// countershade's PLY writer: its binary file is OpenMesh's byte for byte (mesh-usm's files stay as
// they were), and either file reads back to the same floats, colours and polygons.

#include "mesh/ply_writer.h"

#include <gtest/gtest.h>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <fstream>
#include <random>
#include <sstream>

#include "mesh/open_mesh_soup.h"
#include "mesh/ply_reader.h"
#include "test_util.h"

namespace countershade {
namespace {

namespace fs = std::filesystem;

// A coloured grid of quads, with one quad cut into triangles and positions of every magnitude.
PolygonSoup coloured_grid(int side) {
  PolygonSoup soup;
  std::mt19937 random(3);
  std::uniform_real_distribution<float> offset(-1e-3f, 1e-3f);
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      soup.positions.emplace_back(x * 0.1f + offset(random), y * 1e5f, std::ldexp(1.0f, x - y));
      soup.colours.push_back(glm::vec3(x * 17 % 256, y * 29 % 256, (x + y) * 7 % 256) / 255.0f);
    }
  for (int y = 0; y + 1 < side; ++y)
    for (int x = 0; x + 1 < side; ++x) {
      const unsigned v = unsigned(y * side + x), s = unsigned(side);
      if (x == 0 && y == 0) {
        soup.add_face(std::vector<unsigned>{v, v + 1, v + s + 1});
        soup.add_face(std::vector<unsigned>{v, v + s + 1, v + s});
      } else {
        soup.add_face(std::vector<unsigned>{v, v + 1, v + s + 1, v + s});
      }
    }
  return soup;
}

std::string bytes_of(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream all;
  all << in.rdbuf();
  return all.str();
}

TEST(PlyWriter, BinaryFilesAreOpenMeshsByteForByte) {
  testing::TempDir dir;
  const PolygonSoup soup = coloured_grid(30);
  OpenMesh::PolyMesh_ArrayKernelT<> mesh;
  mesh.request_vertex_colors();
  add_soup_to_open_mesh(soup, mesh);
  const OpenMesh::IO::Options options =
      OpenMesh::IO::Options::VertexColor | OpenMesh::IO::Options::Binary;
  ASSERT_TRUE(OpenMesh::IO::write_mesh(mesh, (dir / "open-mesh.ply").string(), options));
  write_ply(dir / "ours.ply", soup, PlyEncoding::binary);
  const std::string reference = bytes_of(dir / "open-mesh.ply");
  EXPECT_GT(reference.size(), 30u * 30u * 15u);
  EXPECT_TRUE(bytes_of(dir / "ours.ply") == reference);
}

TEST(PlyWriter, EitherEncodingReadsBackToTheSameMesh) {
  testing::TempDir dir;
  const PolygonSoup soup = coloured_grid(25);
  for (PlyEncoding encoding : {PlyEncoding::binary, PlyEncoding::ascii}) {
    const fs::path path = dir / (encoding == PlyEncoding::ascii ? "ascii.ply" : "binary.ply");
    write_ply(path, soup, encoding);
    const auto back = read_ply_soup(path);
    ASSERT_TRUE(back) << path;
    EXPECT_EQ(back->positions, soup.positions) << path;
    EXPECT_EQ(back->colours, soup.colours) << path;
    EXPECT_EQ(back->corners, soup.corners) << path;
    EXPECT_EQ(back->face_ends, soup.face_ends) << path;
  }
  EXPECT_NE(bytes_of(dir / "ascii.ply").find("format ascii 1.0\n"), std::string::npos);
}

}  // namespace
}  // namespace countershade
