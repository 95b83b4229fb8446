// 16-bit sets in the adjustment app, on screen: on an X server with a depth-30 visual the app
// confirms a 10-bit framebuffer and shows each stimulus at its 10-bit levels; on a depth-24 one it
// dithers, and a screenshot is exactly the seed's frame. Killed sessions still lose nothing.

#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "app_runner.h"
#include "core/image.h"
#include "runtime/fine_levels.h"
#include "tiny_set.h"

namespace countershade::runtime {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr const char* kSixteenBits = R"("output": {"bits": 16},)";

struct Shot {
  json display, info;
  Image image;
};

// One scripted session on an X server of the given depth, up to a screenshot of a question.
Shot screenshot_session(const testing::TempDir& dir, const fs::path& manifest, int depth,
                        const std::vector<std::string>& more = {}) {
  const std::string name =
      "depth" + std::to_string(depth) + (more.empty() ? "" : "-" + more.back());
  testing::write_file(dir / "keys.txt",
                      "300 enter\n40 right\n40 right\n100 screenshot\n40 close\n");
  testing::XvfbServer x("1280x1024x" + std::to_string(depth));
  std::vector<std::string> flags = {"--script", (dir / "keys.txt").string(), "--frame-clock",
                                    "--screenshot", (dir / (name + ".png")).string()};
  flags.insert(flags.end(), more.begin(), more.end());
  const int status = testing::run_app(x, testing::adjust_args(manifest, dir / name, "P01", flags),
                                      dir / (name + ".log"));
  EXPECT_EQ(status, 0) << testing::read_file(dir / (name + ".log"));
  Shot shot;
  shot.display =
      json::parse(testing::read_file(dir / name / "P01_s01.json"))["runs"][0]["display"]["output"];
  shot.info = json::parse(testing::read_file(dir / (name + ".png.json")));
  shot.image = read_image(dir / (name + ".png"));
  return shot;
}

// Calls check(stimulus code, shown code, x, y) for every channel of both stimuli in the shot.
template <typename Check>
void for_each_stimulus_pixel(const Shot& shot, const fs::path& set, Check check) {
  for (const char* side : {"left", "right"}) {
    const json& r = shot.info[side];
    const Image stimulus = read_image(set / r["file"].get<std::string>());
    const int x0 = r["x"], y0 = r["y"];
    for (int y = 0; y < stimulus.height; ++y)
      for (int x = 0; x < stimulus.width; ++x)
        for (int c = 0; c < 3; ++c)
          check(uint32_t(std::lround(stimulus.at(x, y, c) * 65535)),
                uint32_t(std::lround(shot.image.at(x0 + x, y0 + y, c) * 65535)), uint32_t(x),
                uint32_t(y));
  }
}

TEST(DeepGui, SixteenBitSetsShowAtTenBitsWhereTheReadBackConfirmsThemElseDithered) {
  testing::TempDir dir;
  const auto manifest = testing::make_tiny_set(dir, "", 96, 72, 0.4, kSixteenBits);
  const Shot ten = screenshot_session(dir, manifest, 30);
  EXPECT_EQ(ten.display["path"], "ten-bit");
  EXPECT_EQ(ten.display["ten_bit_read_back"], true);
  EXPECT_EQ(ten.display["framebuffer_bits"], json({10, 10, 10}));
  long wrong = 0, fine = 0;
  for_each_stimulus_pixel(ten, dir / "set", [&](uint32_t code, uint32_t shown, uint32_t, uint32_t) {
    wrong += ten_bit_level(shown) != ten_bit_level(code);
    fine += ten_bit_level(code) % 4 != 0;  // a level no 8-bit display has
  });
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(fine, 1000);

  const Shot dithered = screenshot_session(dir, manifest, 24);
  EXPECT_EQ(dithered.display["path"], "dither");
  EXPECT_EQ(dithered.display["ten_bit_read_back"], false);
  const uint32_t seed = dithered.display["dither_seed"], frame = dithered.info["output_frame"];
  wrong = 0;
  for_each_stimulus_pixel(
      dithered, dir / "set", [&](uint32_t code, uint32_t shown, uint32_t x, uint32_t y) {
        wrong += shown / 257 != dither_level(code, dither_threshold(x, y, frame, seed));
      });
  EXPECT_EQ(wrong, 0);
}

// A session asked for an output path it cannot have, on a depth-24 server: one line saying
// `why`, exit 2, and no answers file.
void expect_refused(const fs::path& dir, const fs::path& manifest, const std::string& path,
                    const std::string& why) {
  testing::XvfbServer x("1280x1024x24");
  const int status =
      testing::run_app(x,
                       testing::adjust_args(manifest, dir / "sessions", "P01",
                                            {"--observer", "simulated:1", "--output-path", path}),
                       dir / "log.txt");
  const std::string log = testing::read_file(dir / "log.txt");
  EXPECT_EQ(status, 2) << log;
  EXPECT_NE(log.find(why), std::string::npos) << log;
  EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 1) << log;
  EXPECT_FALSE(fs::exists(dir / "sessions" / "P01_s01.csv"));
}

// Pseudo-grey on a grey set: every pixel of both stimuli on screen is the reference's three levels
// for the mean of its codes, most of them between two greys. A coloured set is refused in one line.
TEST(DeepGui, PseudoGreyShowsAGreySetAtTheTablesLevelsAndRefusesColour) {
  testing::TempDir dir;
  const auto manifest = testing::make_tiny_set(dir, "", 96, 72, 0.4, kSixteenBits);
  const Shot shot = screenshot_session(dir, manifest, 24, {"--output-path", "pseudo-grey"});
  EXPECT_EQ(shot.display["path"], "pseudo-grey");
  long wrong = 0, between = 0;
  for (const char* side : {"left", "right"}) {
    const json& r = shot.info[side];
    const Image stimulus = read_image(dir / "set" / r["file"].get<std::string>());
    for (int y = 0; y < stimulus.height; ++y)
      for (int x = 0; x < stimulus.width; ++x) {
        uint32_t code[3], shown[3];
        for (int c = 0; c < 3; ++c) {
          code[c] = uint32_t(std::lround(stimulus.at(x, y, c) * 65535));
          shown[c] =
              uint32_t(std::lround(shot.image.at(int(r["x"]) + x, int(r["y"]) + y, c) * 255));
        }
        const uint32_t grey = pseudo_grey_value(code[0], code[1], code[2]);
        wrong += shown[0] != pseudo_grey_level(grey, kPseudoGreyRed) ||
                 shown[1] != pseudo_grey_level(grey, kPseudoGreyGreen) ||
                 shown[2] != pseudo_grey_level(grey, kPseudoGreyBlue);
        between += shown[0] != shown[1] || shown[1] != shown[2];
      }
  }
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(between, 2000);

  testing::TempDir colour;
  std::string scene = testing::kLitCubeScene;
  const std::string grey = "\"albedo\": 0.5";
  scene.replace(scene.find(grey), grey.size(), "\"albedo\": [0.6, 0.45, 0.3]");
  testing::write_file(colour / "cube.json", scene);
  const auto coloured = testing::make_tiny_set_of(colour, kSixteenBits);
  expect_refused(colour.path(), coloured, "pseudo-grey",
                 "pseudo-grey shows achromatic stimuli only, but pixel (");
}

// Asked for ten-bit where the framebuffer has 8 bits: one line, exit 2, and no session files left.
TEST(DeepGui, TenBitIsRefusedWhereTheReadBackFails) {
  testing::TempDir dir;
  const auto manifest = testing::make_tiny_set(dir, "", 96, 72, 0.4, kSixteenBits);
  expect_refused(dir.path(), manifest, "ten-bit", "--output-path: ten-bit");
}

}  // namespace
}  // namespace countershade::runtime
