// The apps' stimulus decoder (runtime/image_decode.h): grey and RGB PNG files into RGBA at 8 and
// 16 bits, checked against the manifest's size and the image size limit before it allocates.

#include "runtime/image_decode.h"

#include <gtest/gtest.h>

#include <cstring>

#include "core/error.h"
#include "core/image.h"
#include "test_util.h"

namespace countershade::runtime {
namespace {

namespace fs = std::filesystem;

TEST(ImageDecode, GreyFillsRedGreenAndBlueAndAlphaIsOpaqueAtBothDepths) {
  testing::TempDir dir;
  Image grey(3, 2, 1);
  for (size_t i = 0; i < grey.pixels.size(); ++i) grey.pixels[i] = float(i) / 5.0f;
  write_image(dir / "grey.png", grey, {16});
  const StimulusImage image{dir / "grey.png", "grey.png", "", 3, 2};
  const std::vector<uint16_t> deep = decode_rgba16(image);
  const std::vector<uint8_t> shallow = decode_rgba(image);
  ASSERT_EQ(deep.size(), 3u * 2u * 4u);
  for (size_t p = 0; p < 6; ++p) {
    const uint16_t code = uint16_t(quantize(float(p) / 5.0f, 16));
    EXPECT_EQ(deep[4 * p], code) << p;
    EXPECT_EQ(deep[4 * p + 1], code) << p;
    EXPECT_EQ(deep[4 * p + 2], code) << p;
    EXPECT_EQ(deep[4 * p + 3], 65535) << p;
    EXPECT_EQ(shallow[4 * p + 3], 255) << p;
  }
  EXPECT_EQ(shallow[4 * 5], 255);  // the last pixel is white at 8 bits too
}

TEST(ImageDecode, AnImageOfAnotherSizeThanTheManifestsIsRefused) {
  testing::TempDir dir;
  write_image(dir / "rgb.png", Image(4, 3, 3, 0.5f));
  try {
    decode_rgba({dir / "rgb.png", "rgb.png", "", 4, 4});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("differs from the manifest"), std::string::npos)
        << e.what();
  }
}

// Found by fuzz/png_fuzzer.cpp: a manifest may list sizes up to 2^20, and a file whose header
// claimed the same 100000 × 100000 pixels made the decoder allocate 120 GB (std::bad_alloc, the
// app's "failure"). It is refused at the size limit, as read_image refuses it.
TEST(ImageDecode, AHeaderOverTheSizeLimitIsRefusedBeforeAllocating) {
  const fs::path file = testing::source_dir() / "fuzz/corpus/png/finding-stimulus-huge-size.png";
  for (auto decode : {+[](const StimulusImage& i) { (void)decode_rgba(i); },
                      +[](const StimulusImage& i) { (void)decode_rgba16(i); }}) {
    try {
      decode({file, "huge.png", "", 100000, 100000});
      FAIL() << "no error";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("the limit is 16384x16384"), std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace countershade::runtime
