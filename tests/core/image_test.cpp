#include "core/image.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "test_util.h"

namespace countershade {
namespace {

TEST(Image, PngRoundTripIsExactAt8And16Bits) {
  testing::TempDir dir;
  Image image(7, 3, 3);
  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = float(i % 256) / 255.0f;
  write_image(dir / "a.png", image, {8});
  Image back = read_image(dir / "a.png");
  ASSERT_EQ(back.width, 7);
  ASSERT_EQ(back.channels, 3);
  for (size_t i = 0; i < image.pixels.size(); ++i) EXPECT_FLOAT_EQ(back.pixels[i], image.pixels[i]);

  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = float(i * 1000 % 65536) / 65535.0f;
  write_image(dir / "b.png", image, {16});
  back = read_image(dir / "b.png");
  for (size_t i = 0; i < image.pixels.size(); ++i) EXPECT_NEAR(back.pixels[i], image.pixels[i], 1e-7);
}

TEST(Image, ExrKeepsFloatsAndWritesAtomically) {
  testing::TempDir dir;
  Image image(4, 4, 1);
  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = 3.25f * float(i);
  write_image(dir / "d.exr", image);
  Image back = read_image(dir / "d.exr");
  EXPECT_EQ(back.pixels, image.pixels);
  // Only the final file is left: no temporary siblings.
  int files = 0;
  for (auto& e : std::filesystem::directory_iterator(dir.path())) files += e.is_regular_file();
  EXPECT_EQ(files, 1);
}

TEST(Image, QuantizeRoundsToNearest) {
  EXPECT_EQ(quantize(0.5f / 255.0f + 1e-6f, 8), 1u);
  EXPECT_EQ(quantize(1.0f, 8), 255u);
  EXPECT_EQ(quantize(-0.2f, 16), 0u);
  EXPECT_EQ(quantize(1.5f, 16), 65535u);
}

TEST(Image, UnreadableFilesAreInputErrors) {
  testing::TempDir dir;
  EXPECT_THROW(read_image(dir / "missing.png"), InputError);
  testing::write_file(dir / "empty.png", "");
  EXPECT_THROW(read_image(dir / "empty.png"), InputError);
  testing::write_file(dir / "junk.png", "this is not a png");
  EXPECT_THROW(read_image(dir / "junk.png"), InputError);
}

}  // namespace
}  // namespace countershade
