// 16-bit stimuli in the browser: the page draws them with WebGL2 (SwiftShader in headless
// Chromium) through the app's dither. 64 consecutive frames read back from the page equal the
// app's reference frames bit for bit (runtime::dither_level and dither_threshold, for the frame
// numbers and the session seed), and each pixel's mean over them lies within 0.02 of a level of
// its 16-bit value. Without WebGL2 the page says so and stores nothing.

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "../adjust/tiny_set.h"
#include "core/image.h"
#include "runtime/fine_levels.h"
#include "runtime/study.h"

namespace countershade::runtime {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string base64_decode(const std::string& text) {
  static const std::string digits =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  uint32_t bits = 0;
  int count = 0;
  for (char c : text) {
    if (c == '=') break;
    bits = (bits << 6) | uint32_t(digits.find(c));
    if ((count += 6) >= 8) out.push_back(char((bits >> (count -= 8)) & 0xff));
  }
  return out;
}

// A 16-bit tiny set, exported; returns the study folder.
fs::path exported_deep_set(const testing::TempDir& dir) {
  const fs::path manifest =
      testing::make_tiny_set(dir, "", 96, 72, 0.4, R"("output": {"bits": 16},)");
  const auto run = testing::run_cli("export-web " + manifest.string() + " -o " +
                                    (dir / "web").string() + " --study adjust");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  return dir / "web";
}

json read_back(const fs::path& study, const fs::path& out, const std::string& chromium_args = "") {
  const auto run = testing::run_program("bash -c", "'cd " + testing::source_dir().string() +
                                                       " && CHROMIUM_ARGS=\"" + chromium_args +
                                                       "\" node web/tools/browser-dither.mjs " +
                                                       study.string() + " " + out.string() + "'");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  return json::parse(testing::read_file(out));
}

TEST(WebDither, SixtyFourFramesEqualTheAppsDitherBitForBit) {
  testing::TempDir dir;
  const fs::path web = exported_deep_set(dir);
  const json frames = read_back(web, dir / "frames.json")["frames"];
  ASSERT_EQ(frames.size(), 64u);
  const Study study = load_study(dir / "set/manifest.json", std::nullopt);
  const uint32_t seed =
      uint32_t(session_seed(study.config.seed.value_or(study.manifest_seed), "P01", 1));
  const json item = frames[0]["item"];
  const std::string file = item["file"];
  const size_t image = std::stoul(file.substr(file.find('/') + 1)) - 1;
  const Image codes = read_image(study.images[image].file);
  const int w = item["width"], h = item["height"];
  ASSERT_EQ(codes.width, w);
  long differing = 0;
  std::vector<double> sum(size_t(w) * size_t(h) * 3, 0);
  for (const json& f : frames) {
    EXPECT_EQ(f["item"], item);
    const std::string pixels = base64_decode(f["pixels"]);
    ASSERT_EQ(pixels.size(), size_t(w) * size_t(h) * 4);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c) {
          const auto v = uint32_t(std::lround(codes.at(x, y, c) * 65535.0f));
          const uint32_t expected =
              dither_level(v, dither_threshold(uint32_t(x), uint32_t(y), f["frame"], seed));
          const auto shown = uint32_t(uint8_t(pixels[(size_t(y) * size_t(w) + size_t(x)) * 4 + c]));
          differing += shown != expected;
          sum[(size_t(y) * size_t(w) + size_t(x)) * 3 + size_t(c)] += shown;
        }
  }
  EXPECT_EQ(differing, 0);
  double worst = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c)
        worst =
            std::max(worst, std::abs(sum[(size_t(y) * size_t(w) + size_t(x)) * 3 + size_t(c)] / 64 -
                                     codes.at(x, y, c) * 255.0));
  EXPECT_LE(worst, 0.02);
}

TEST(WebDither, WithoutWebGl2ThePageSaysSoAndStoresNothing) {
  testing::TempDir dir;
  const fs::path web = exported_deep_set(dir);
  const json result = read_back(web, dir / "frames.json", "--disable-webgl --disable-webgl2");
  ASSERT_TRUE(result.contains("unsupported")) << result.dump();
  EXPECT_NE(result["unsupported"].get<std::string>().find("WebGL2"), std::string::npos);
  EXPECT_EQ(result["stored"], 0);
}

}  // namespace
}  // namespace countershade::runtime
