#include "mesh/mesh_io.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "test_util.h"

namespace countershade {
namespace {

TEST(MeshIo, LoadsSharedMeshes) {
  TriangleMesh bunny = load_mesh(testing::mesh_path("stanford-bunny.obj"));
  EXPECT_EQ(bunny.vertex_count(), 35947u);
  EXPECT_EQ(bunny.triangle_count(), 69451u);
  EXPECT_FALSE(bunny.has_uvs());

  TriangleMesh spot = load_mesh(testing::mesh_path("spot.obj"));
  EXPECT_EQ(spot.vertex_count(), 2930u);
  EXPECT_EQ(spot.triangle_count(), 5856u);
  ASSERT_TRUE(spot.has_uvs());
  EXPECT_EQ(spot.corner_uvs.size(), 3 * spot.triangle_count());
  for (const auto& uv : spot.corner_uvs) {  // the unit square, give or take a seam margin
    EXPECT_GT(uv.x, -0.1f);
    EXPECT_LT(uv.y, 1.1f);
  }
}

TEST(MeshIo, TriangulatesPolygonsAndReadsOtherFormats) {
  testing::TempDir dir;
  auto quad =
      testing::write_file(dir / "quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  EXPECT_EQ(load_mesh(quad).triangle_count(), 2u);
  auto off = testing::write_file(dir / "tri.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_EQ(load_mesh(off).triangle_count(), 1u);
  auto ply = testing::write_file(
      dir / "tri.ply",
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0 255 0 0\n1 0 0 0 255 0\n0 1 0 0 0 255\n3 0 1 2\n");
  TriangleMesh m = load_mesh(ply);
  ASSERT_TRUE(m.has_vertex_colors());
  EXPECT_FLOAT_EQ(m.vertex_colors[1].g, 1.0f);
}

TEST(MeshIo, BadMeshesAreInputErrorsNamingTheFile) {
  testing::TempDir dir;
  struct Case {
    std::string name, text, expected;
  } cases[] = {
      {"nan.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n", "NaN or infinite"},
      {"inf.obj", "v 0 0 0\nv 1 inf 0\nv 0 1 0\nf 1 2 3\n", "NaN or infinite"},
      {"range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n", "out of range"},
      {"zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n",
       "face index '0' is not a non-zero integer"},
      {"noface.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "no faces"},
      {"degenerate.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n", "degenerate"},
      {"repeated.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 4\n", "degenerate"},
      {"nonmanifold.obj",
       "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n", "non-manifold"},
      {"empty.obj", "", "empty"},
      {"mesh.xyz", "1 2 3\n", "unsupported mesh format"},
  };
  for (const auto& c : cases) {
    auto path = testing::write_file(dir / c.name, c.text);
    std::string message = testing::input_error_of([&] { load_mesh(path); });
    EXPECT_NE(message.find(path.string()), std::string::npos) << c.name << ": " << message;
    EXPECT_NE(message.find(c.expected), std::string::npos) << c.name << ": " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << c.name;
  }
  EXPECT_NE(
      testing::input_error_of([&] { load_mesh(dir / "missing.obj"); }).find("no such mesh file"),
      std::string::npos);
}

// Files the fuzzer found (fuzz/corpus/mesh/finding-*): OpenMesh looped forever on a PLY header
// without end_header or with control characters in a property line, converted OBJ vertex colours
// above 1 to bytes with undefined behaviour, and allocated whatever counts a header declared.
TEST(MeshIo, MalformedHeadersAreRefusedBeforeOpenMeshReadsThem) {
  testing::TempDir dir;
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float "
      "z\n";
  struct Case {
    std::string name, text, expected;
  } cases[] = {
      {"no_end.ply", ply + "element face 1\nproperty list uchar int vertex_indices\n",
       "no end_header"},
      {"misspelt.ply", ply + "end_heade\n0 0 0\n", "line 7: unexpected PLY header line"},
      {"control.ply", ply + "property list uchar i" + std::string(3, '\0') + "x\nend_header\n",
       "control or non-ASCII"},
      {"property.ply", ply + "property float\nend_header\n", "expected 'property TYPE NAME'"},
      {"format.ply", "ply\nformat fancy 1.0\nend_header\n", "expected 'format"},
      {"version.ply", "ply\nformat binary_little_endian !.0\nend_header\n",
       "line 2: expected 'format"},
      {"count.ply",
       "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float "
       "x\nend_header\n",
       "declares 4000000000 elements"},
      {"keyword.ply", ply + "vertex 1 2 3\nend_header\n", "unexpected PLY header line"},
      {"orphan.ply", "ply\nformat binary_little_endian 1.0\nproperty float u\nend_header\n",
       "line 3: a property before any element"},
      {"element.ply", ply + "element faec 4\nend_header\n", "element 'faec' is not read"},
      {"stray.ply", ply + "end_header\n0 0 0\n1 0 0\n0 1 0-3rty 2\n",
       "vertex 2: '0-3rty' is not a number"},
      {"fraction.ply",
       ply + "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 "
             "1 0\n3 0 1.5 2\n",
       "face 0: '1.5' is not an integer"},
      {"few.ply", ply + "end_header\n0 0 0\n1 0 0\n0 1\n",
       "vertex 2: the file ends before all its values"},
      {"count.off", "OFF\n4000000000 1 0\n0 0 0\n", "declares 4000000000 vertices"},
      {"binary.off", "OFF BINARY\n", "binary OFF"},
      {"nocount.off", "OFF\n# nothing\n", "no vertex and face counts"},
      {"face.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3i 0 1 2\n",
       "line 6: '3i' is not a finite number"},
      {"index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
       "vertex index 3 is out of range (0..2)"},
      {"short.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "ends before face 1"},
      {"colour.off", "COFF\n3 1 0\n0 0 0 2.5 0 0\n1 0 0 0 0 0\n0 1 0 0 0 0\n3 0 1 2\n",
       "colour must be"},
      {"nocolour.off", "COFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
       "line 3: a COFF vertex needs a colour"},
      {"repeated.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 1\n",
       "line 6: face 0 is degenerate"},
      {"variant.off", "4OFF\n3 1 0\n", "OFF variant '4OFF' is not supported"},
      {"garbage.stl", "not an STL at all", "neither a binary STL"},
      {"colour.obj", "v 0 0 0 1 2 3\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
       "vertex 0 has a colour outside [0, 1]"},
      {"formfeed.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf\f1/1 2 3\n",
       "line 4: face texture coordinate index 1 is out of range (1..0)"},
      {"normal.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//2 2//1 3//1\n",
       "face normal index 2 is out of range (1..1)"},
      // OpenMesh skips a line that starts with a vertical tab or a form feed (after spaces), so
      // that vertex does not exist: counting it let a face index past OpenMesh's vertices.
      {"vtab.obj", "v 0 0 0\nv 0 1 0\n\vv 0 0 1\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 3/3 2/2\n",
       "line 7: face vertex index 3 is out of range (1..2)"},
      {"formfeed_line.obj", "v 0 0 0\nv 0 1 0\n \fv 0 0 1\nf 1 3 2\n",
       "line 4: face vertex index 3 is out of range (1..2)"},
      {"junk.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1x/0 2 3\n",
       "face index '1x' is not a non-zero integer"},
      {"zero_texcoord.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/0 2 3\n",
       "face index '0' is not a non-zero integer"},
      {"beyond.obj", "v 0 1e129 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
       "vertex 0 has a NaN or infinite coordinate"},
      {"word.obj", "v 0 0 0\nv 1 0 0\nv 0 1 21e?c1\nf 1 2 3\n", "line 3: '21e?c1' is not a number"},
      {"texcoord.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt nan 0\nf 1/1 2/1 3/1\n",
       "texture coordinate 0 needs two finite numbers"},
      {"nancolour.obj", "v 0 0 0 nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
       "vertex 0 has a NaN or infinite value"},
  };
  for (const auto& c : cases) {
    auto path = testing::write_file(dir / c.name, c.text);
    std::string message = testing::input_error_of([&] { load_mesh(path); });
    EXPECT_NE(message.find(c.expected), std::string::npos) << c.name << ": " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << c.name;
  }
  // Valid files with colours in range, comments and CRLF line ends still load.
  auto coloured =
      testing::write_file(dir / "ok.obj", "v 0 0 0 1 0.5 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n");
  EXPECT_EQ(load_mesh(coloured).triangles.size(), 1u);
  auto commented =
      testing::write_file(dir / "ok.ply", ply +
                                              "comment made by hand\nelement face 1\n"
                                              "property list uchar int vertex_indices\nend_header\n"
                                              "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_EQ(load_mesh(commented).triangles.size(), 1u);
}

// countershade reads OFF itself: counts on the magic line or the next, comments, polygons, and
// COFF colours as bytes or fractions.
TEST(MeshIo, ReadsOffWithCommentsPolygonsAndColours) {
  testing::TempDir dir;
  auto bytes = testing::write_file(
      dir / "bytes.off",
      "COFF 4 1 0 # counts on the magic line\n0 0 0 255 0 0\n1 0 0 0 255 0 255\n"
      "# a comment line\n1 1 0 0 0 255\n0 1 0 255 255 255\n4 0 1 2 3 9 9 9\n");
  TriangleMesh m = load_mesh(bytes);
  EXPECT_EQ(m.positions.size(), 4u);
  EXPECT_EQ(m.triangles.size(), 2u);
  ASSERT_EQ(m.vertex_colors.size(), 4u);
  EXPECT_FLOAT_EQ(m.vertex_colors[1].g, 1.0f);
  EXPECT_FLOAT_EQ(m.vertex_colors[0].g, 0.0f);
  auto fractions = testing::write_file(
      dir / "fractions.off", "COFF\n3 1 0\n0 0 0 0.5 0 1\n1 0 0 0 0 0\n0 1 0 1 1 1\n3 0 1 2\n");
  EXPECT_NEAR(load_mesh(fractions).vertex_colors[0].r, 128.0f / 255.0f,
              1e-6f);  // stored as bytes, like PLY colours
}

}  // namespace
}  // namespace countershade
