// Bad input found by trying the commands as a hostile but realistic user would: every case ends
// quickly with exit status 2 and one line naming the file or the option and the problem.

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

#include "core/image.h"
#include "core/text.h"
#include "test_util.h"

namespace countershade {
namespace {

namespace fs = std::filesystem;

const char* kScene = R"({
  "version": 1,
  "camera": {"eye": [0, 1, 4], "target": [0, 0, 0], "width": 40, "height": 30},
  "render": {"spp": 2},
  "objects": [{"shape": {"type": "sphere", "radius": 1, "subdivisions": 3}OBJECT_EXTRA}],
  "lights": [{"type": "directional", "direction": [1, 1, 1], "irradiance": 2}]
})";

std::string scene_with(const std::string& object_extra) {
  std::string s = kScene;
  s.replace(s.find("OBJECT_EXTRA"), 12, object_extra);
  return s;
}

// CRC-32 of PNG chunks (bitwise; a test needs no table).
uint32_t crc32(const std::string& bytes) {
  uint32_t crc = 0xFFFFFFFFu;
  for (unsigned char b : bytes) {
    crc ^= b;
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

std::string big_endian(uint32_t v) { return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)}; }

std::string png_chunk(const std::string& type_and_data) {
  return big_endian(uint32_t(type_and_data.size() - 4)) + type_and_data +
         big_endian(crc32(type_and_data));
}

// A PNG whose header claims width × height pixels, with an empty image data chunk.
std::string png_header_only(uint32_t width, uint32_t height) {
  const std::string ihdr =
      "IHDR" + big_endian(width) + big_endian(height) + std::string("\x08\x02\x00\x00\x00", 5);
  return std::string("\x89PNG\r\n\x1a\n", 8) + png_chunk(ihdr) + png_chunk("IDAT") +
         png_chunk("IEND");
}

struct Case {
  std::string arguments, expected;  // expected: a part of the one-line message
};

// A hang (say, on a header that claims a huge image) shows as the test's ctest timeout: no clock
// here, so that the test passes on a busy machine.
void expect_refused(const Case& c) {
  const auto r = testing::run_cli(c.arguments);
  EXPECT_EQ(r.exit_code, 2) << c.arguments << "\n" << r.output;
  EXPECT_EQ(testing::count_lines(r.output), 1) << c.arguments << "\n" << r.output;
  EXPECT_NE(r.output.find(c.expected), std::string::npos) << c.arguments << "\n" << r.output;
}

// A misspelt option is named even where a required argument is missing too (the parser checks the
// latter first), in the main program and in the server's.
TEST(BadInput, AnUnknownOptionIsNamedBeforeAMissingArgument) {
  testing::TempDir dir;
  const fs::path scene = testing::write_file(dir / "scene.json", scene_with(""));
  for (const Case& c :
       std::vector<Case>{{"render " + scene.string() + " --outptu x.png", "not expected: --outptu"},
                         {"render --bogus", "not expected: --bogus"},
                         {"serve --bogus", "not expected: --bogus"},
                         {"stimuli --spp 4", "not expected: --spp"},
                         {"render " + scene.string(), "--output is required"}})
    expect_refused(c);
}

TEST(BadInput, RenderRefusesSingularTransformsNonFiniteNumbersAndAbsurdWidths) {
  testing::TempDir dir;
  const std::string scene = testing::write_file(dir / "s.json", scene_with("")).string();
  const std::string singular =
      testing::write_file(
          dir / "singular.json",
          scene_with(R"(, "transform": {"matrix": [1,0,0,0, 0,0,0,0, 0,0,1,0, 0,0,0,1]})"))
          .string();
  // Found by the fuzzer: a translation beyond float's range made positions infinite.
  const std::string far =
      testing::write_file(dir / "far.json",
                          scene_with(R"(, "transform": {"translate": [0, 0, 4e88]})"))
          .string();
  std::string box = scene_with("");
  box.replace(box.find(R"("type": "sphere", "radius": 1, "subdivisions": 3)"), 48,
              R"("type": "box", "subdivisions": 4096)");
  const std::string huge_box = testing::write_file(dir / "huge_box.json", box).string();
  const std::string out = (dir / "o.png").string();
  for (const Case& c : std::vector<Case>{
           {"render " + singular + " -o " + out + " --method usm3d --lambda 1 --sigma 0.1",
            "singular"},
           {"render " + far + " -o " + out, "objects[0].transform: puts vertices outside ±1e15"},
           {"render " + huge_box + " -o " + out,
            "would make about 201720000 triangles (the limit is 50000000)"},
           {"render " + scene + " -o " + out + " --exposure nan", "finite"},
           {"render " + scene + " -o " + out + " --exposure inf", "finite"},
           {"render " + scene + " -o " + out + " --method usm3d --lambda 1 --sigma 1e300",
            "smoothing iterations"},
           {"render " + scene + " -o " + out + " --method usm3d --lambda 1 --iterations 2147483647",
            "--iterations"},
           {"render " + scene + " -o " + out +
                " --method usm3d --lambda 1 --sigma 0.1 --refine 1e-9",
            "the limit is 50000000"},
           {"render " + scene + " -o " + out +
                " --method usm3d --lambda 1 --sigma 0.1 --refine nan",
            "--refine"},
       })
    expect_refused(c);
  EXPECT_FALSE(fs::exists(out));
}

TEST(BadInput, ImagesThatClaimHugeSizesOrHoldNaNAreRefusedByName) {
  testing::TempDir dir;
  const std::string bomb =
      testing::write_file(dir / "bomb.png", png_header_only(60000, 60000)).string();
  Image nan_texture(4, 4, 3);
  nan_texture.pixels[5] = std::numeric_limits<float>::quiet_NaN();
  write_image(dir / "nan.exr", nan_texture);
  nan_texture.pixels[5] = std::numeric_limits<float>::infinity();
  write_image(dir / "inf.exr", nan_texture);
  std::string plane =
      scene_with(R"(, "material": {"texture": ")" + (dir / "nan.exr").string() + R"("})");
  plane.replace(plane.find(R"("type": "sphere", "radius": 1, "subdivisions": 3)"), 48,
                R"("type": "plane", "size": 2)");
  const std::string textured = testing::write_file(dir / "textured.json", plane).string();
  plane.replace(plane.find("nan.exr"), 7, "inf.exr");
  const std::string infinite = testing::write_file(dir / "infinite.json", plane).string();
  for (const Case& c : std::vector<Case>{
           {"image-usm " + bomb + " -o " + (dir / "o.png").string() +
                " --method usm2d --lambda 1 --sigma-px 2",
            "16384"},
           {"render " + textured + " -o " + (dir / "t.png").string(),
            "pixel (1, 0) channel 2 is not a number"},
           {"render " + infinite + " -o " + (dir / "t.png").string(),
            "pixel (1, 0) channel 2 is not a finite number"},
       })
    expect_refused(c);
}

// A truncated or damaged PNG (as an image or as a texture) is one line of ours: libpng used to
// print its own "libpng error:" line first.
TEST(BadInput, TruncatedAndDamagedPngsAreOneLine) {
  testing::TempDir dir;
  Image picture(64, 48, 3);
  for (size_t i = 0; i < picture.pixels.size(); ++i) picture.pixels[i] = float(i % 97) / 96.0f;
  write_image(dir / "whole.png", picture);
  const std::string whole = testing::read_file(dir / "whole.png");
  const std::string truncated =
      testing::write_file(dir / "truncated.png", whole.substr(0, whole.size() / 2)).string();
  std::string flipped = whole;
  flipped[flipped.size() / 2] = char(flipped[flipped.size() / 2] ^ 0x5a);
  const std::string damaged = testing::write_file(dir / "damaged.png", flipped).string();
  const std::string no_end =
      testing::write_file(dir / "no_end.png", whole.substr(0, whole.size() - 12)).string();
  std::string plane = scene_with(R"(, "material": {"texture": ")" + truncated + R"("})");
  plane.replace(plane.find(R"("type": "sphere", "radius": 1, "subdivisions": 3)"), 48,
                R"("type": "plane", "size": 2)");
  const std::string textured = testing::write_file(dir / "textured.json", plane).string();
  const std::string usm =
      " -o " + (dir / "o.png").string() + " --method usm2d --lambda 1 --sigma-px 2";
  for (const Case& c : std::vector<Case>{
           {"image-usm " + truncated + usm, "truncated.png: truncated PNG: chunk IDAT at byte"},
           {"image-usm " + damaged + usm, "damaged.png: damaged PNG: chunk IDAT at byte"},
           {"image-usm " + no_end + usm, "no_end.png: truncated PNG: the file ends at byte"},
           {"render " + textured + " -o " + (dir / "t.png").string(),
            "truncated.png: truncated PNG"},
       })
    expect_refused(c);
}

// Outputs are checked before any work: a failed run leaves an existing output untouched.
TEST(BadInput, OutputsAreCheckedBeforeAnythingIsWritten) {
  testing::TempDir dir;
  Image grey(16, 16, 3, 0.5f);
  write_image(dir / "in.png", grey);
  write_image(dir / "exist.png", Image(16, 16, 3, 0.1f));
  testing::write_file(dir / "keep.png", "keep");
  const std::string before = testing::read_file(dir / "exist.png");
  expect_refused({"image-usm " + (dir / "in.png").string() + " -o " + (dir / "exist.png").string() +
                      " --method usm2d --lambda 1 --sigma-px 2 --aux " +
                      (dir / "keep.png").string(),
                  "is a file, not a folder"});
  EXPECT_EQ(testing::read_file(dir / "exist.png"), before);
  EXPECT_EQ(testing::read_file(dir / "keep.png"), "keep");
  const std::string scene = testing::write_file(dir / "s.json", scene_with("")).string();
  expect_refused({"render " + scene + " -o /proc/o.png", "not writable"});
  expect_refused({"render " + scene + " -o " + (dir / "o.png").string() + " --aux " +
                      (dir / "keep.png").string(),
                  "is a file, not a folder"});
  EXPECT_FALSE(fs::exists(dir / "o.png"));
  expect_refused({"sheet " + (dir / "in.png").string() + "=a " + (dir / "missing.png").string() +
                      "=b -o " + (dir / "sheet.png").string(),
                  "missing.png: no such image"});
  EXPECT_FALSE(fs::exists(dir / "sheet.png"));
}

// `sheet` puts the images in rows of --columns, thumbnails at a whole-factor shrink, a short last
// row allowed: two 64-px images and one more in rows of two. A caption wider than its thumbnail
// widens every column, so that it never runs into the next one.
TEST(SheetCommand, PlacesEveryImageInRowsAtItsThumbnailSize) {
  testing::TempDir dir;
  write_image(dir / "a.png", Image(64, 48, 3, 1.0f));
  write_image(dir / "b.png", Image(64, 48, 3, 0.0f));
  const auto r = testing::run_cli("sheet " + (dir / "a.png").string() + "=w " +
                                  (dir / "b.png").string() + "=k " + (dir / "a.png").string() +
                                  " -o " + (dir / "s.png").string() + " --columns 2 --width 32");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Image sheet = read_image(dir / "s.png");
  // 10 px margin, thumbnails 32×24 with a 24-px gap, 56 px above the first row.
  EXPECT_EQ(sheet.width, 10 + 2 * (32 + 24));
  EXPECT_EQ(sheet.height, 56 + 2 * (24 + 24));
  EXPECT_FLOAT_EQ(sheet.at(10 + 16, 56 + 12, 0), 1.0f);       // a, row 1
  EXPECT_FLOAT_EQ(sheet.at(10 + 56 + 16, 56 + 12, 0), 0.0f);  // b, row 1
  EXPECT_FLOAT_EQ(sheet.at(10 + 16, 56 + 48 + 12, 0), 1.0f);  // a again, row 2
  EXPECT_NEAR(sheet.at(10 + 56 + 16, 56 + 48 + 12, 0), 0.5f,
              1.0f / 255);  // nothing: the grey surround
  const std::string caption = "usm3d, σ = 0.12, λ = 3";
  const auto wide = testing::run_cli("sheet '" + (dir / "a.png").string() + "=" + caption + "' " +
                                     (dir / "b.png").string() + " -o " + (dir / "w.png").string() +
                                     " --columns 2 --width 32");
  ASSERT_EQ(wide.exit_code, 0) << wide.output;
  const int pitch = 24 + text_width(caption, 12);
  ASSERT_GT(pitch, 32 + 24);
  EXPECT_EQ(read_image(dir / "w.png").width, 10 + 2 * pitch);
  EXPECT_FLOAT_EQ(read_image(dir / "w.png").at(10 + pitch + 16, 56 + 12, 0),
                  0.0f);  // b, one pitch on
}

TEST(BadInput, SimulateRefusesNonFiniteDesignsAndRunawaySizes) {
  testing::TempDir dir;
  const std::string out = " -o " + (dir / "sim.csv").string();
  for (const Case& c : std::vector<Case>{
           {"simulate" + out + " --lambda-step nan", "finite"},
           {"simulate" + out + " --low nan", "finite"},
           {"simulate" + out + " --answer-sd inf", "finite"},
           {"simulate" + out + " --weak-fraction nan", "finite"},
           {"simulate" + out + " --lambda-step 0", "--lambda-step: must be 1e-09 to 1e+06, not 0"},
           // A step of 1e-300 wrote lambda_index -2147483648 and λ -0: a corrupt CSV.
           {"simulate" + out + " --lambda-step 1e-300",
            "--lambda-step: must be 1e-09 to 1e+06, not 1e-300"},
           {"simulate" + out + " --lambda-max 1e300", "--lambda-max: must be 1e-09 to 1e+06"},
           {"simulate" + out + " --lambda-max 1e6 --lambda-step 1e-3",
            "more than 100000 grid values"},
           {"simulate" + out + " --subjects 100000 --repetitions 100", "the limit is 10000000"},
       })
    expect_refused(c);
  EXPECT_FALSE(fs::exists(dir / "sim.csv"));
}

TEST(BadInput, ScenesNameTheKeyOfAnOutOfRangeSeed) {
  testing::TempDir dir;
  std::string s = scene_with("");
  s.replace(s.find(R"("spp": 2)"), 8, R"("spp": 2, "seed": 18446744073709551615)");
  const std::string scene = testing::write_file(dir / "seed.json", s).string();
  expect_refused({"render " + scene + " -o " + (dir / "o.png").string(), "18446744073709551615"});
}

// A message quotes what it found; a binary file or a file name with a newline must still give one
// readable line.
TEST(BadInput, MessagesQuotingBinaryBytesOrNewlinesStayOneReadableLine) {
  testing::TempDir dir;
  const std::string png =
      testing::write_file(dir / "not-a-manifest.json", png_header_only(4, 4)).string();
  expect_refused({"audit " + png + " -o " + (dir / "report").string(), "\\x89"});
  expect_refused(
      {"render '" + (dir / "two\nlines.json").string() + "' -o " + (dir / "o.png").string(),
       "two\\x0alines.json"});
}

}  // namespace
}  // namespace countershade
