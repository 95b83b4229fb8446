// End-to-end tests of `countershade image-usm` and of the render path for the image-space methods.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/image.h"
#include "test_util.h"

namespace countershade {
namespace {

using testing::count_lines;
using testing::run_cli;

const char* kSphereOnPlaneScene = R"({
  "version": 1,
  "camera": {"eye": [0.3, 1.2, 4], "target": [0, 0.3, 0], "width": 64, "height": 48},
  "render": {"spp": 2},
  "objects": [
    {"shape": {"type": "plane", "size": 6, "subdivisions": 4}, "material": {"albedo": [0.6, 0.55, 0.5]}},
    {"shape": {"type": "sphere", "radius": 0.6, "subdivisions": 3}, "transform": {"translate": [0, 0.6, 0]},
     "material": {"albedo": [0.3, 0.5, 0.7]}}
  ],
  "lights": [{"type": "directional", "direction": [1, 2, 1], "irradiance": 2}, {"type": "ambient", "radiance": 0.2}]
})";

// Pixels with a depth edge in their 3×3 neighbourhood (another object, background against surface,
// eye depths more than 5 % apart): where depth-usm samples a rendered pixel's area again.
std::vector<bool> depth_edges(const Image& object, const Image& depth) {
  auto valid = [](float d) { return std::isfinite(d) && d > 0.0f; };
  std::vector<bool> edge(depth.pixels.size(), false);
  for (int y = 0; y < depth.height; ++y)
    for (int x = 0; x < depth.width; ++x)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = std::clamp(x + dx, 0, depth.width - 1),
                    ny = std::clamp(y + dy, 0, depth.height - 1);
          const float d = depth.at(x, y), e = depth.at(nx, ny);
          if (object.at(x, y) != object.at(nx, ny) || valid(d) != valid(e) ||
              (valid(d) && std::abs(d - e) > 0.05f * std::min(d, e)))
            edge[size_t(y) * depth.width + x] = true;
        }
  return edge;
}

// How two renders' pixels differ: the largest difference in code values off the depth edges and
// on them.
struct Difference {
  int off_edges = 0, on_edges = 0;
};
Difference code_difference(const std::filesystem::path& a, const std::filesystem::path& b,
                           const std::vector<bool>& edge) {
  const Image first = read_image(a), second = read_image(b);
  EXPECT_EQ(first.pixels.size(), second.pixels.size());
  Difference d;
  for (size_t i = 0; i < std::min(first.pixels.size(), second.pixels.size()); ++i) {
    const int levels = int(std::lround(std::abs(first.pixels[i] - second.pixels[i]) * 255.0f));
    int& largest = edge[i / 3] ? d.on_edges : d.off_edges;
    largest = std::max(largest, levels);
  }
  return d;
}

// A photograph-style input built from a render: the PNG plus its depth written by --aux, re-read
// by image-usm. Away from depth edges depth-usm gives exactly what the in-renderer path gives; on
// them the renderer samples each pixel's area again and a depth file has one depth per pixel.
// usm2d takes its detail from the render before quantisation where it has one, and a PNG has only
// the codes: the two differ by λ times at most half a step, so by at most one code.
TEST(ImageUsmCli, ImagePlusDepthRoundTripEqualsTheRendererPath) {
  testing::TempDir dir;
  auto scene = testing::write_file(dir / "s.json", kSphereOnPlaneScene);
  ASSERT_EQ(run_cli("render " + scene.string() + " -o " + (dir / "photo.png").string() + " --aux " +
                    (dir / "aux").string())
                .exit_code,
            0);
  const std::vector<bool> edge =
      depth_edges(read_image(dir / "aux/object_id.exr"), read_image(dir / "aux/depth.exr"));
  struct Case {
    std::string options;
    int off_edges = 0;  // the largest difference allowed off the depth edges
    bool edges_differ = true;
  } cases[] = {
      {"--method depth-usm --operator darken --lambda 0.8 --kernel 5%"},
      {"--method depth-usm --operator color --lambda 1.5 --kernel 3 --space rgb"},
      {"--method depth-usm --operator contrast --contrast equalize --lambda 2 --sigma-px 4 --space "
       "lab"},
      {"--method depth-usm --operator add --lambda -0.5 --kernel 4% --depth-mapping zbuffer"},
      {"--method usm2d --lambda 1.2 --sigma-percent 1", 1, false}};
  int k = 0;
  for (const auto& c : cases) {
    std::string a = (dir / ("a" + std::to_string(k) + ".png")).string(),
                b = (dir / ("b" + std::to_string(k) + ".png")).string();
    ++k;
    auto r1 = run_cli("render " + scene.string() + " -o " + a + " " + c.options);
    ASSERT_EQ(r1.exit_code, 0) << r1.output;
    auto r2 = run_cli("image-usm " + (dir / "photo.png").string() + " --depth " +
                      (dir / "aux/depth.exr").string() + " -o " + b + " " + c.options);
    ASSERT_EQ(r2.exit_code, 0) << r2.output;
    const Difference d = code_difference(a, b, edge);
    EXPECT_LE(d.off_edges, c.off_edges) << c.options;
    if (c.edges_differ)
      EXPECT_GT(d.on_edges, 0) << c.options;  // the edges were sampled again
    else
      EXPECT_LE(d.on_edges, c.off_edges) << c.options;
    EXPECT_NE(testing::read_file(a), testing::read_file(dir / "photo.png")) << c.options;
  }
}

TEST(ImageUsmCli, DisparityMapsAndAuxiliaryOutput) {
  testing::TempDir dir;
  // Left half near (disparity 40), right half far (disparity 10), one invalid column (0).
  Image photo(40, 20, 3, 0.5f), disparity(40, 20, 1);
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 40; ++x) disparity.at(x, y) = x == 39 ? 0.0f : (x < 20 ? 40.0f : 10.0f);
  write_image(dir / "im.png", photo);
  write_image(dir / "disp.pfm", disparity);
  auto r =
      run_cli("image-usm " + (dir / "im.png").string() + " --depth " + (dir / "disp.pfm").string() +
              " --depth-kind disparity -o " + (dir / "out.png").string() +
              " --method depth-usm --operator darken --lambda 1 --sigma-px 3 --aux " +
              (dir / "aux").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  Image d = read_image(dir / "aux/depth_normalized.exr"),
        dd = read_image(dir / "aux/spatial_importance.exr");
  EXPECT_FLOAT_EQ(d.at(5, 10), 0.0f);   // near (largest disparity)
  EXPECT_FLOAT_EQ(d.at(30, 10), 1.0f);  // far
  EXPECT_FLOAT_EQ(d.at(39, 10), 1.0f);  // invalid counts as background
  EXPECT_LT(dd.at(21, 10), 0.0f);       // background side of the edge
  EXPECT_TRUE(std::filesystem::exists(dir / "aux/depth_blurred.exr"));
  Image out = read_image(dir / "out.png");
  EXPECT_LT(out.at(21, 10, 0), out.at(35, 10, 0));  // darkened next to the edge
  EXPECT_FLOAT_EQ(out.at(5, 10, 0), read_image(dir / "im.png").at(5, 10, 0));  // far from the edge
}

TEST(ImageUsmCli, BadInputExitsWithTwoAndWritesNothing) {
  testing::TempDir dir;
  write_image(dir / "im.png", Image(20, 10, 3, 0.5f));
  write_image(dir / "small.exr", Image(10, 10, 1, 1.0f));
  write_image(dir / "depth.exr", Image(20, 10, 1, 1.0f));
  testing::write_file(dir / "empty.png", "");
  std::string im = (dir / "im.png").string(), out = (dir / "out.png").string();
  std::string depth = " --depth " + (dir / "depth.exr").string();
  struct Case {
    std::string args, expected;
  } cases[] = {
      {im + " --depth " + (dir / "small.exr").string() + " -o " + out +
           " --method depth-usm --lambda 1 --kernel 5%",
       "depth map is 10x10 but the image is 20x10"},
      {(dir / "empty.png").string() + depth + " -o " + out +
           " --method depth-usm --lambda 1 --kernel 5%",
       "empty.png"},
      {(dir / "missing.png").string() + depth + " -o " + out +
           " --method depth-usm --lambda 1 --kernel 5%",
       "no such image file"},
      {im + depth + " -o " + out + " --method depth-usm --lambda 1 --kernel 0%", "--kernel"},
      {im + depth + " -o " + out + " --method depth-usm --lambda 1 --kernel 60%", "--kernel"},
      {im + depth + " -o " + out + " --method depth-usm --lambda 1 --kernel five", "--kernel"},
      {im + depth + " -o " + out + " --method depth-usm --operator blur --lambda 1 --kernel 5%",
       "--operator"},
      {im + depth + " -o " + out + " --method depth-usm --lambda nan --kernel 5%", "--lambda"},
      {im + " -o " + out + " --method depth-usm --lambda 1 --kernel 5%", "--depth"},
      {im + depth + " -o " + out + " --method usm3d --lambda 1 --sigma 0.1",
       "--method: usm3d works on a rendered scene"},
      {im + depth + " -o " + out + " --method usm3d --lambda 1 --kernel 5%",
       "--kernel: usm3d has no parameter"},
      {im + depth + " -o " + (dir / "out.gif").string() + " --method usm2d --lambda 1 --kernel 5%",
       "output must be"},
      {im + depth + " -o " + out +
           " --method depth-usm --operator color --cold 1,2 --lambda 1 --kernel 5%",
       "--cold"},
  };
  for (const auto& c : cases) {
    auto r = run_cli("image-usm " + c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.output;
    EXPECT_EQ(count_lines(r.output), 1) << r.output;
    EXPECT_NE(r.output.find(c.expected), std::string::npos) << r.output;
  }
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace countershade
