// End-to-end tests of `countershade render` through the real binary.

#include <gtest/gtest.h>

#include "core/image.h"
#include "test_util.h"

namespace countershade {
namespace {

using testing::count_lines;
using testing::run_cli;

const char* kRenderScene = R"({
  "version": 1,
  "camera": {"eye": [0, 1, 4], "target": [0, 0, 0], "width": 40, "height": 30},
  "render": {"spp": 2},
  "objects": [{"shape": {"type": "sphere", "radius": 1, "subdivisions": 3}}],
  "lights": [{"type": "directional", "direction": [1, 1, 1], "irradiance": 2}]
})";

TEST(RenderCli, HelpIsAvailableEverywhere) {
  auto top = run_cli("--help");
  EXPECT_EQ(top.exit_code, 0);
  EXPECT_NE(top.output.find("render"), std::string::npos);
  auto sub = run_cli("render --help");
  EXPECT_EQ(sub.exit_code, 0);
  EXPECT_NE(sub.output.find("--spp"), std::string::npos);
  EXPECT_EQ(run_cli("--version").exit_code, 0);
}

TEST(RenderCli, RendersPngExrAndAuxiliaryBuffers) {
  testing::TempDir dir;
  auto scene = testing::write_file(dir / "s.json", kRenderScene);
  auto r = run_cli("render " + scene.string() + " -o " + (dir / "out.png").string() +
                   " --width 20 --height 16 --aux " + (dir / "aux").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  Image png = read_image(dir / "out.png");
  EXPECT_EQ(png.width, 20);
  EXPECT_EQ(png.height, 16);
  for (const char* f : {"depth.exr", "normal.exr", "object_id.exr"})
    EXPECT_TRUE(std::filesystem::exists(dir / "aux" / f)) << f;
  EXPECT_EQ(read_image(dir / "aux/depth.exr").channels, 1);

  r = run_cli("render " + scene.string() + " -o " + (dir / "out.exr").string() + " --bits 16");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read_image(dir / "out.exr").width, 40);
  r = run_cli("render " + scene.string() + " -o " + (dir / "out16.png").string() + " --bits 16");
  ASSERT_EQ(r.exit_code, 0) << r.output;
}

TEST(RenderCli, OneSizeGivenAloneKeepsTheScenesAspectRatio) {
  testing::TempDir dir;
  auto scene = testing::write_file(dir / "s.json", kRenderScene);  // 40×30
  const std::string base = "render " + scene.string() + " -o ";
  ASSERT_EQ(run_cli(base + (dir / "w.png").string() + " --width 20").exit_code, 0);
  ASSERT_EQ(run_cli(base + (dir / "h.png").string() + " --height 9").exit_code, 0);
  const Image w = read_image(dir / "w.png"), h = read_image(dir / "h.png");
  EXPECT_EQ(w.width, 20);
  EXPECT_EQ(w.height, 15);
  EXPECT_EQ(h.width, 12);
  EXPECT_EQ(h.height, 9);
}

TEST(RenderCli, Usm3dAtLambdaZeroMatchesTheUnenhancedPngByteForByte) {
  testing::TempDir dir;
  auto scene = testing::write_file(dir / "s.json", kRenderScene);
  std::string base = "render " + scene.string() + " -o ";
  ASSERT_EQ(run_cli(base + (dir / "none.png").string()).exit_code, 0);
  auto r = run_cli(base + (dir / "zero.png").string() + " --method usm3d --lambda 0 --sigma 0.2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(testing::read_file(dir / "zero.png"), testing::read_file(dir / "none.png"));
  r = run_cli(base + (dir / "strong.png").string() +
              " --method usm3d --lambda 2 --sigma-fraction 0.1 --refine 0.05");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("iterations"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("clipped pixels"), std::string::npos) << r.output;
  EXPECT_NE(testing::read_file(dir / "strong.png"), testing::read_file(dir / "none.png"));
}

// --reference writes the plain image of the same render: a uniformly lit ball (ambient light only,
// sampled adaptively) has no contrast to enhance, so usm3d at λ = 1 must give the reference's
// bytes at every pixel, silhouettes included; at λ = 0 too. A reference that is not an image is
// refused before any work.
TEST(RenderCli, TheReferenceComesFromTheSameSamplesAsTheStimulus) {
  testing::TempDir dir;
  auto scene = testing::write_file(dir / "uniform.json", R"({
    "version": 1,
    "camera": {"eye": [0, 1, 4], "target": [0, 0, 0], "width": 48, "height": 36},
    "render": {"noise": {"target": 0.5, "min_spp": 4, "max_spp": 256}},
    "display": {"background": 0.1},
    "objects": [{"shape": {"type": "sphere", "radius": 1, "subdivisions": 3}, "material": {"albedo": 0.6}}],
    "lights": [{"type": "ambient", "radiance": 1.0}]
  })");
  for (const char* lambda : {"1", "0"}) {
    auto r = run_cli("render " + scene.string() + " -o " + (dir / "enhanced.png").string() +
                     " --reference " + (dir / "plain.png").string() +
                     " --method usm3d --sigma 0.3 --lambda " + lambda);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(read_image(dir / "enhanced.png").pixels, read_image(dir / "plain.png").pixels)
        << "lambda " << lambda;
  }
  auto bad =
      run_cli("render " + scene.string() + " -o " + (dir / "x.png").string() + " --reference " +
              (dir / "plain.exr").string() + " --method usm3d --sigma 0.3 --lambda 1");
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("plain.exr"), std::string::npos) << bad.output;
}

// λ = 1e300 overflows the noise model's terms (inf − inf); the stimulus saturates and its noise
// is reported as unbounded. It used to index a table with NaN and crash.
TEST(RenderCli, AnAbsurdLambdaSaturatesAndReportsUnboundedNoise) {
  testing::TempDir dir;
  auto scene = testing::write_file(dir / "s.json", kRenderScene);
  for (const char* lambda : {"1e300", "-1e300"}) {
    auto r = run_cli("render " + scene.string() + " -o " + (dir / "o.png").string() +
                     " --method usm3d --sigma 0.2 --lambda " + lambda);
    ASSERT_EQ(r.exit_code, 0) << lambda << "\n" << r.output;
    EXPECT_NE(r.output.find("noise inf L* RMS"), std::string::npos) << r.output;
    EXPECT_EQ(read_image(dir / "o.png").width, 40);
  }
}

TEST(RenderCli, BadInputExitsWithTwoAndOneLine) {
  testing::TempDir dir;
  auto scene = testing::write_file(dir / "s.json", kRenderScene);
  auto bad = testing::write_file(dir / "bad.json", "{\"version\": 1, \"camera\": ");
  std::string out = (dir / "o.png").string();
  struct Case {
    std::string args, expected;
  } cases[] = {
      {"render " + bad.string() + " -o " + out, "bad.json: malformed JSON"},
      {"render " + (dir / "missing.json").string() + " -o " + out, "missing.json: no such file"},
      {"render " + scene.string() + " -o " + (dir / "nofolder/o.png").string(),
       "output folder does not exist"},
      {"render " + scene.string() + " -o " + (dir / "o.jpg").string(), "output must be"},
      {"render " + scene.string() + " -o " + out + " --spp 0", "--spp"},
      {"render " + scene.string() + " -o " + out + " --bits 12", "--bits"},
      {"render " + scene.string() + " -o " + out + " --method magic", "--method"},
      {"render " + scene.string() + " -o " + out + " --method usm3d --lambda 1",
       "exactly one of --sigma"},
      {"render " + scene.string() + " -o " + out + " --method usm3d --lambda 1 --sigma -2",
       "--sigma"},
      {"render " + scene.string() + " -o " + out + " --method usm3d --lambda nan --sigma 0.1",
       "--lambda"},
      {"render " + scene.string() + " -o " + out + " --method usm3d --lambda 1 --sigma-fraction 3",
       "--sigma-fraction"},
      {"render " + scene.string(), "--output is required"},
      {"frobnicate", "frobnicate"},
  };
  for (const auto& c : cases) {
    auto r = run_cli(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.output;
    EXPECT_EQ(count_lines(r.output), 1) << r.output;
    EXPECT_NE(r.output.find(c.expected), std::string::npos) << r.output;
  }
  EXPECT_FALSE(std::filesystem::exists(out));
}

// usm3d reports its iterations per object: ten objects show eight and a count of the rest, so a
// scene of hundreds of objects or components keeps a summary line a terminal can show.
TEST(RenderCli, TheSummaryLineShortensLongParameterLists) {
  testing::TempDir dir;
  std::string objects;
  for (int i = 0; i < 10; ++i)
    objects += std::string(i ? "," : "") + R"({"name": "ball)" + std::to_string(i) +
               R"(", "shape": {"type": "sphere", "radius": 0.2, "subdivisions": 1},
                 "transform": {"translate": [)" +
               std::to_string(0.5 * i - 2.25) + ", 0, 0]}}";
  auto scene = testing::write_file(dir / "s.json", R"({
    "version": 1,
    "camera": {"eye": [0, 1, 6], "target": [0, 0, 0], "width": 40, "height": 30},
    "render": {"spp": 2},
    "objects": [)" + objects + R"(],
    "lights": [{"type": "directional", "direction": [1, 1, 1], "irradiance": 2}]
  })");
  auto r = run_cli("render " + scene.string() + " -o " + (dir / "out.png").string() +
                   " --method usm3d --lambda 1 --sigma 0.1");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find(R"("ball0":)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(R"("ball7":)"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find(R"("ball8":)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(",… 2 more}"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(R"("sigma":0.1)"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace countershade
