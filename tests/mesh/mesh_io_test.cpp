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
  auto quad = testing::write_file(dir / "quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  EXPECT_EQ(load_mesh(quad).triangle_count(), 2u);
  auto off = testing::write_file(dir / "tri.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_EQ(load_mesh(off).triangle_count(), 1u);
  auto ply = testing::write_file(dir / "tri.ply",
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
      {"zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n", "out of range"},
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
  EXPECT_NE(testing::input_error_of([&] { load_mesh(dir / "missing.obj"); }).find("no such mesh file"), std::string::npos);
}

}  // namespace
}  // namespace countershade
