// `texture-filter` in `texture` mode renders exactly what a scene whose texture file was filtered
// beforehand by `countershade image-filter` renders.

#include <gtest/gtest.h>

#include <cstdlib>

#include "core/image.h"
#include "test_util.h"

namespace countershade {
namespace {

std::string spot_scene(const std::string& texture, const std::string& encoding) {
  return R"({"version": 1,
    "camera": {"eye": [1.6, 0.9, 1.9], "target": [0, 0.4, 0], "fov": 30, "width": 160, "height": 120},
    "render": {"spp": 2},
    "display": {"background": [0.2, 0.2, 0.2]},
    "objects": [{"name": "spot", "mesh": ")" +
         testing::mesh_path("spot.obj").string() + R"(", "fit": true,
                 "material": {"texture": ")" +
         texture + R"(", "texture_encoding": ")" + encoding + R"("}}],
    "lights": [{"type": "directional", "direction": [0.5, 1.0, 0.7], "irradiance": 2.2}]})";
}

TEST(ImageFilterCli, TextureModeEqualsATextureFilteredBeforehand) {
  testing::TempDir dir;
  ::setenv("COUNTERSHADE_CACHE", (dir / "cache").c_str(), 1);
  const std::string filter = " --filter bilateral --sigma 1.5 --sigma-r 8 --lambda 0.7";
  const auto filtered =
      testing::run_cli("image-filter " + testing::mesh_path("spot_texture.png").string() + " " +
                       (dir / "filtered.exr").string() + filter);
  ASSERT_EQ(filtered.exit_code, 0) << filtered.output;
  testing::write_file(dir / "plain.json",
                      spot_scene(testing::mesh_path("spot_texture.png").string(), "srgb"));
  testing::write_file(dir / "prefiltered.json",
                      spot_scene((dir / "filtered.exr").string(), "linear"));
  const auto a = testing::run_cli("render " + (dir / "plain.json").string() + " -o " +
                                  (dir / "a.png").string() +
                                  " --method texture-filter --mode texture" + filter);
  ASSERT_EQ(a.exit_code, 0) << a.output;
  const auto b = testing::run_cli("render " + (dir / "prefiltered.json").string() + " -o " +
                                  (dir / "b.png").string());
  ASSERT_EQ(b.exit_code, 0) << b.output;
  const auto plain = testing::run_cli("render " + (dir / "plain.json").string() + " -o " +
                                      (dir / "plain.png").string());
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_EQ(read_image(dir / "a.png").pixels, read_image(dir / "b.png").pixels);
  EXPECT_EQ(testing::read_file(dir / "a.png"), testing::read_file(dir / "b.png"));
  EXPECT_NE(read_image(dir / "a.png").pixels,
            read_image(dir / "plain.png").pixels);  // the filter did something
}

TEST(ImageFilterCli, BadFilterKeysExitTwoWithOneLine) {
  testing::TempDir dir;
  const auto r =
      testing::run_cli("image-filter " + testing::mesh_path("spot_texture.png").string() + " " +
                       (dir / "out.exr").string() + " --filter dog --sigma-r 3");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(testing::count_lines(r.output), 1) << r.output;
  EXPECT_NE(r.output.find("--sigma-r: applies to filter bilateral only"), std::string::npos)
      << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.exr"));
}

}  // namespace
}  // namespace countershade
