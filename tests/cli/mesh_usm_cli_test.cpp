// End-to-end tests of `countershade mesh-usm` through the real binary.

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "core/color.h"
#include "mesh/colored_mesh.h"
#include "mesh/mesh_io.h"
#include "mesh/primitives.h"
#include "test_util.h"

namespace countershade {
namespace {

using testing::count_lines;
using testing::run_cli;

// A 21×21 grid with a dark left half and a light right half, as an ASCII PLY with colours.
std::string step_edge_ply(bool with_colors = true) {
  TriangleMesh grid = make_plane(2.0, 20);
  std::ostringstream ply;
  ply << "ply\nformat ascii 1.0\nelement vertex " << grid.vertex_count()
      << "\nproperty float x\nproperty float y\nproperty float z\n";
  if (with_colors) ply << "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  ply << "element face " << grid.triangle_count()
      << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& p : grid.positions) {
    ply << p.x << " " << p.y << " " << p.z;
    if (with_colors) ply << (p.x < -1e-6 ? " 90 70 60" : " 170 150 140");
    ply << "\n";
  }
  for (const auto& t : grid.triangles) ply << "3 " << t.x << " " << t.y << " " << t.z << "\n";
  return ply.str();
}

TEST(MeshUsmCli, EnhancesColoursAndKeepsEverythingElse) {
  testing::TempDir dir;
  auto in = testing::write_file(dir / "step.ply", step_edge_ply());
  auto out = dir / "out.ply";
  auto r = run_cli("mesh-usm " + in.string() + " -o " + out.string() + " --lambda 1.5 --sigma 0.3");
  ASSERT_EQ(r.exit_code, 0) << r.output;

  TriangleMesh before = load_mesh(in), after = load_mesh(out);
  ASSERT_EQ(after.vertex_count(), before.vertex_count());
  EXPECT_EQ(after.positions, before.positions);
  EXPECT_EQ(after.triangles, before.triangles);
  int darker = 0, lighter = 0;
  for (size_t v = 0; v < before.vertex_count(); ++v) {
    double x = before.positions[v].x;
    double L0 = srgb_to_lab(glm::dvec3(before.vertex_colors[v])).L,
           L1 = srgb_to_lab(glm::dvec3(after.vertex_colors[v])).L;
    if (x < -0.05 && x > -0.25) darker += L1 < L0 - 1.0;  // undershoot on the dark side of the edge
    if (x > 0.05 && x < 0.25) lighter += L1 > L0 + 1.0;   // overshoot on the light side
    if (std::abs(x) > 0.95 && std::abs(before.positions[v].z) < 0.9) {
      EXPECT_NEAR(L1, L0, 1.0) << "far from the edge the colour stays";
    }
  }
  EXPECT_GT(darker, 10);
  EXPECT_GT(lighter, 10);

  // The same mesh as text, on request.
  const auto text = dir / "out-ascii.ply";
  r = run_cli("mesh-usm " + in.string() + " -o " + text.string() +
              " --lambda 1.5 --sigma 0.3 --ply-format ascii");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(testing::read_file(text).rfind("ply\nformat ascii 1.0\n", 0), 0u);
  const TriangleMesh as_text = load_mesh(text);
  EXPECT_EQ(as_text.positions, after.positions);
  EXPECT_EQ(as_text.triangles, after.triangles);
  EXPECT_EQ(as_text.vertex_colors, after.vertex_colors);

  // λ = 0 keeps every colour exactly.
  r = run_cli("mesh-usm " + in.string() + " -o " + out.string() + " --lambda 0 --iterations 5");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(load_mesh(out).vertex_colors, before.vertex_colors);
}

TEST(MeshUsmCli, BadInputExitsWithTwoAndWritesNothing) {
  testing::TempDir dir;
  auto good = testing::write_file(dir / "good.ply", step_edge_ply());
  auto plain = testing::write_file(dir / "plain.ply", step_edge_ply(false));
  auto nonmanifold = testing::write_file(
      dir / "nm.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n");
  auto degenerate = testing::write_file(dir / "deg.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  std::string out = (dir / "out.ply").string();
  struct Case {
    std::string args, expected;
  } cases[] = {
      {plain.string() + " -o " + out + " --lambda 1 --sigma 0.1", "no vertex colours"},
      {nonmanifold.string() + " -o " + out + " --lambda 1 --sigma 0.1", "non-manifold"},
      {degenerate.string() + " -o " + out + " --lambda 1 --sigma 0.1", "degenerate"},
      {good.string() + " -o " + out + " --lambda nan --sigma 0.1", "--lambda"},
      {good.string() + " -o " + out + " --lambda 1 --sigma -0.1", "--sigma"},
      {good.string() + " -o " + out + " --lambda 1 --sigma nan", "--sigma"},
      {good.string() + " -o " + out + " --lambda 1", "exactly one of --sigma or --iterations"},
      {good.string() + " -o " + out + " --lambda 1 --sigma 0.1 --iterations 4", "exactly one of"},
      {good.string() + " -o " + out + " --lambda 1 --iterations 0", "--iterations"},
      {good.string() + " -o " + (dir / "out.obj").string() + " --lambda 1 --sigma 0.1",
       "must be a .ply"},
      {(dir / "missing.ply").string() + " -o " + out + " --lambda 1 --sigma 0.1",
       "no such mesh file"},
  };
  for (const auto& c : cases) {
    auto r = run_cli("mesh-usm " + c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.output;
    EXPECT_EQ(count_lines(r.output), 1) << r.output;
    EXPECT_NE(r.output.find(c.expected), std::string::npos) << r.output;
  }
  EXPECT_FALSE(std::filesystem::exists(out));
  for (auto& entry : std::filesystem::directory_iterator(dir.path()))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos)
        << "temporary file left behind";
}

}  // namespace
}  // namespace countershade
