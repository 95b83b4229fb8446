// The libpng codec against OpenImageIO's: the same file bytes for what it writes, the same values
// for what it reads, and the rest declined to OpenImageIO (codecs/png_image_codec.cpp).

#include <gtest/gtest.h>
#include <png.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include "codecs/image_codec.h"
#include "core/image.h"
#include "core/plugin_library.h"
#include "core/random.h"
#include "test_util.h"

namespace countershade {
namespace {

using codecs::ImageCodec;
using codecs::ImageFileSpec;
using codecs::Sample;

const ImageCodec& libpng_codec() { return plugin<ImageCodec>("png_codec"); }
const ImageCodec& openimageio_codec() { return plugin<ImageCodec>("image_codec"); }

// Noise over a smooth ramp: rows that each filter and compress differently.
template <typename T>
std::vector<T> test_codes(const ImageFileSpec& spec, uint64_t seed) {
  std::vector<T> codes(size_t(spec.width) * spec.height * spec.channels);
  SampleStream noise(seed, 1, 2, 3);
  const double top = spec.bits == 8 ? 255.0 : 65535.0;
  for (size_t i = 0; i < codes.size(); ++i) {
    const double ramp =
        double(i % size_t(spec.width * spec.channels)) / (spec.width * spec.channels);
    codes[i] = T(std::min(top, top * (0.8 * ramp + 0.2 * noise.next())));
  }
  return codes;
}

template <typename T>
void expect_same_file(const ImageFileSpec& spec, Sample sample, bool fast) {
  testing::TempDir dir;
  const std::vector<T> codes = test_codes<T>(spec, uint64_t(spec.width + spec.channels));
  ASSERT_TRUE(libpng_codec().takes(spec, sample));
  ASSERT_EQ(libpng_codec().write((dir / "ours.png").string(), spec, sample, codes.data(), fast),
            "");
  ASSERT_EQ(
      openimageio_codec().write((dir / "oiio.png").string(), spec, sample, codes.data(), fast), "");
  const std::string ours = testing::read_file(dir / "ours.png");
  const std::string theirs = testing::read_file(dir / "oiio.png");
  const auto differ = std::mismatch(ours.begin(), ours.end(), theirs.begin(), theirs.end());
  EXPECT_TRUE(ours == theirs) << ours.size() << " and " << theirs.size()
                              << " bytes, first difference at " << (differ.first - ours.begin())
                              << ", " << spec.width << "x" << spec.height << "x" << spec.channels
                              << " at " << spec.bits << " bits, fast " << fast;
}

TEST(PngCodec, WritesOpenImageIOsFilesByteForByte) {
  // 300 × 200 RGB at 16 bits spans several image data chunks.
  for (const auto& [width, height] : {std::pair{37, 23}, std::pair{300, 200}, std::pair{1, 1}})
    for (int channels : {1, 3})
      for (bool fast : {true, false}) {
        expect_same_file<uint8_t>({width, height, channels, 8}, Sample::uint8, fast);
        expect_same_file<uint16_t>({width, height, channels, 16}, Sample::uint16, fast);
      }
}

// Reads `file` through both codecs as `sample` and compares the bits.
template <typename T>
void expect_same_values(const std::filesystem::path& file, Sample sample) {
  std::string error;
  const auto ours = libpng_codec().open(file.string(), error);
  ASSERT_TRUE(ours) << error;
  const auto theirs = openimageio_codec().open(file.string(), error);
  ASSERT_TRUE(theirs) << error;
  EXPECT_EQ(ours->spec().bits, theirs->spec().bits);
  ASSERT_EQ(ours->spec().channels, theirs->spec().channels);
  const size_t n = size_t(ours->spec().width) * ours->spec().height * ours->spec().channels;
  std::vector<T> a(n), b(n);
  ASSERT_EQ(ours->read(sample, a.data()), "");
  ASSERT_EQ(theirs->read(sample, b.data()), "");
  EXPECT_EQ(std::memcmp(a.data(), b.data(), n * sizeof(T)), 0)
      << file << " as sample " << int(sample);
}

TEST(PngCodec, ReadsEveryCodeAsOpenImageIODoes) {
  testing::TempDir dir;
  std::vector<uint8_t> bytes(256 * 3);
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = uint8_t(i / 3 + i % 3);
  ASSERT_EQ(libpng_codec().write((dir / "8.png").string(), {256, 1, 3, 8}, Sample::uint8,
                                 bytes.data(), true),
            "");
  std::vector<uint16_t> words(65536);
  for (size_t i = 0; i < words.size(); ++i) words[i] = uint16_t(i);
  ASSERT_EQ(libpng_codec().write((dir / "16.png").string(), {256, 256, 1, 16}, Sample::uint16,
                                 words.data(), true),
            "");
  for (const char* name : {"8.png", "16.png"}) {
    expect_same_values<float>(dir / name, Sample::float32);
    expect_same_values<uint8_t>(dir / name, Sample::uint8);
    expect_same_values<uint16_t>(dir / name, Sample::uint16);
  }
}

// A PNG written by libpng with what this codec declines: a palette, transparency, gamma,
// interlacing or grey with alpha.
void write_unusual_png(const std::filesystem::path& path, int color_type, int interlace,
                       bool gamma) {
  FILE* file = std::fopen(path.c_str(), "wb");
  ASSERT_TRUE(file);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  png_init_io(png, file);
  png_set_IHDR(png, info, 6, 5, 8, color_type, interlace, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_color palette[4] = {{0, 0, 0}, {255, 0, 0}, {0, 255, 0}, {10, 20, 30}};
  if (color_type == PNG_COLOR_TYPE_PALETTE) png_set_PLTE(png, info, palette, 4);
  if (gamma) png_set_gAMA(png, info, 1.0 / 2.2);
  png_write_info(png, info);
  const int passes = png_set_interlace_handling(png);
  const int channels = color_type == PNG_COLOR_TYPE_GRAY_ALPHA ? 2 : color_type == 2 ? 3 : 1;
  std::vector<png_byte> row(size_t(6 * channels));
  for (int pass = 0; pass < passes; ++pass)
    for (int y = 0; y < 5; ++y) {
      for (size_t i = 0; i < row.size(); ++i) row[i] = png_byte((i * 37 + size_t(y) * 11) % 4);
      png_write_row(png, row.data());
    }
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  std::fclose(file);
}

TEST(PngCodec, DeclinesWhatItCannotReadExactlyAndOpenImageIOReadsIt) {
  testing::TempDir dir;
  struct Case {
    const char* name;
    int color_type, interlace;
    bool gamma;
  };
  for (const Case& c :
       {Case{"palette.png", PNG_COLOR_TYPE_PALETTE, PNG_INTERLACE_NONE, false},
        Case{"grey-alpha.png", PNG_COLOR_TYPE_GRAY_ALPHA, PNG_INTERLACE_NONE, false},
        Case{"interlaced.png", PNG_COLOR_TYPE_RGB, PNG_INTERLACE_ADAM7, false},
        Case{"gamma.png", PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE, true}}) {
    write_unusual_png(dir / c.name, c.color_type, c.interlace, c.gamma);
    std::string error = "unset";
    EXPECT_FALSE(libpng_codec().open((dir / c.name).string(), error)) << c.name;
    EXPECT_EQ(error, "") << c.name << ": declined, not refused";
    // read_image goes to OpenImageIO for it and gets OpenImageIO's values.
    const Image image = read_image(dir / c.name);
    const auto theirs = openimageio_codec().open((dir / c.name).string(), error);
    ASSERT_TRUE(theirs) << error;
    std::vector<float> values(image.pixels.size());
    ASSERT_EQ(theirs->read(Sample::float32, values.data()), "");
    EXPECT_TRUE(std::equal(values.begin(), values.end(), image.pixels.begin(), image.pixels.end()))
        << c.name;
  }
  // A JPEG file under a .png name: declined, and read by OpenImageIO as before.
  const std::vector<uint8_t> grey(8 * 6, 77);
  ASSERT_EQ(openimageio_codec().write((dir / "photo.jpg").string(), {8, 6, 1, 8}, Sample::uint8,
                                      grey.data(), false),
            "");
  std::filesystem::rename(dir / "photo.jpg", dir / "photo.png");
  std::string error = "unset";
  EXPECT_FALSE(libpng_codec().open((dir / "photo.png").string(), error));
  EXPECT_EQ(error, "");
  EXPECT_EQ(read_image(dir / "photo.png").width, 8);
  // Alpha and two-channel images are written by OpenImageIO, which unpremultiplies alpha.
  EXPECT_FALSE(libpng_codec().takes({4, 4, 4, 8}, Sample::uint8));
  EXPECT_FALSE(libpng_codec().takes({4, 4, 2, 16}, Sample::uint16));
  EXPECT_FALSE(libpng_codec().takes({4, 4, 3, 8}, Sample::uint16));
}

TEST(PngCodec, ADamagedFileIsRefusedWithLibpngsReasonNotDeclined) {
  testing::TempDir dir;
  const std::vector<uint8_t> codes(64 * 64, 7);
  ASSERT_EQ(libpng_codec().write((dir / "a.png").string(), {64, 64, 1, 8}, Sample::uint8,
                                 codes.data(), 1),
            "");
  std::string bytes = testing::read_file(dir / "a.png");
  bytes[16] = char(0x7f);  // the width's top byte: IHDR's CRC no longer matches
  testing::write_file(dir / "b.png", bytes);
  std::string error;
  EXPECT_FALSE(libpng_codec().open((dir / "b.png").string(), error));
  EXPECT_NE(error.find("CRC"), std::string::npos) << error;
}

// A command that reads and writes plain PNG files never loads OpenImageIO's 260 libraries.
TEST(PngCodec, APngOnlyCommandDoesNotLoadOpenImageIO) {
  testing::TempDir dir;
  Image image(16, 12, 3);
  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = float(i % 7) / 7.0f;
  write_image(dir / "in.png", image, {8});
  const auto loaded = [&](const std::string& output) {
    const auto run = testing::run_program(
        "LD_DEBUG=files LD_DEBUG_OUTPUT=" + (dir / "ld").string() + " " COUNTERSHADE_BINARY,
        "image-usm " + (dir / "in.png").string() + " -o " + (dir / output).string() +
            " --method usm2d --sigma-px 2 --lambda 1");
    EXPECT_EQ(run.exit_code, 0) << run.output;
    std::string log;
    for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
      if (entry.path().filename().string().rfind("ld.", 0) == 0) {
        log += testing::read_file(entry.path());
        std::filesystem::remove(entry.path());
      }
    EXPECT_NE(log.find("libcountershade_png_codec.so"), std::string::npos);
    return log.find("libOpenImageIO") != std::string::npos;
  };
  EXPECT_FALSE(loaded("out.png"));
  EXPECT_TRUE(loaded("out.exr"));  // the check can fail: EXR goes through OpenImageIO
}

}  // namespace
}  // namespace countershade
