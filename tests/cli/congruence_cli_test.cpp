// `countershade congruence` on a rendered image and its depth: one summary line whose last number
// is the score, a false-colour map, and one-line errors for bad input.

#include <gtest/gtest.h>

#include <string>

#include "core/image.h"
#include "test_util.h"

namespace countershade {
namespace {

TEST(CongruenceCli, ScoresARenderAndWritesItsMap) {
  testing::TempDir dir;
  const auto scene = testing::write_file(dir / "cube.json", testing::kLitCubeScene);
  const auto render =
      testing::run_cli("render " + scene.string() + " -o " + (dir / "cube.png").string() +
                       " --aux " + (dir / "aux").string());
  ASSERT_EQ(render.exit_code, 0) << render.output;
  const auto r =
      testing::run_cli("congruence " + (dir / "cube.png").string() + " --depth " +
                       (dir / "aux/depth.exr").string() + " --map " + (dir / "map.png").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(testing::count_lines(r.output), 1) << r.output;
  const double score = std::stod(r.output.substr(r.output.rfind(' ') + 1));
  EXPECT_GT(score, 0.0);
  EXPECT_LE(score, 1.0);
  const Image map = read_image(dir / "map.png");
  EXPECT_EQ(map.channels, 3);
}

TEST(CongruenceCli, BadInputIsOneLine) {
  testing::TempDir dir;
  write_image(dir / "a.png", Image(8, 6, 3, 0.5f));
  write_image(dir / "d.exr", Image(7, 6, 1, 2.0f));
  const std::string image = (dir / "a.png").string();
  struct Case {
    std::string arguments, expected;
  } cases[] = {
      {"congruence " + image + " --depth " + (dir / "d.exr").string(),
       "depth map is 7x6 but the image is 8x6"},
      {"congruence " + image + " --depth " + (dir / "none.exr").string(),
       "none.exr: no such image file"},
      {"congruence " + image, "--depth is required"},
      {"congruence " + image + " --depth " + (dir / "d.exr").string() + " --map " +
           (dir / "no/map.png").string(),
       "output folder does not exist"},
  };
  for (const Case& c : cases) {
    const auto r = testing::run_cli(c.arguments);
    EXPECT_EQ(r.exit_code, 2) << c.arguments << "\n" << r.output;
    EXPECT_EQ(testing::count_lines(r.output), 1) << r.output;
    EXPECT_NE(r.output.find(c.expected), std::string::npos) << r.output;
  }
}

}  // namespace
}  // namespace countershade
