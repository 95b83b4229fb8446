#include "core/image.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

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

  for (size_t i = 0; i < image.pixels.size(); ++i)
    image.pixels[i] = float(i * 1000 % 65536) / 65535.0f;
  write_image(dir / "b.png", image, {16});
  back = read_image(dir / "b.png");
  for (size_t i = 0; i < image.pixels.size(); ++i)
    EXPECT_NEAR(back.pixels[i], image.pixels[i], 1e-7);
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

namespace countershade {
namespace {

TEST(Image, PfmRoundTripsBottomUpRowsAndInfinity) {
  testing::TempDir dir;
  Image disparity(3, 2, 1);
  disparity.pixels = {1.0f, 2.0f, 3.0f, 4.0f, INFINITY, 6.5f};  // top row first in memory
  write_image(dir / "d.pfm", disparity);
  std::string bytes = testing::read_file(dir / "d.pfm");
  EXPECT_EQ(bytes.rfind("Pf\n3 2\n-1.0\n", 0), 0u);
  float first_stored;  // the file's first row is the image's bottom row
  std::memcpy(&first_stored, bytes.data() + std::string("Pf\n3 2\n-1.0\n").size(), 4);
  EXPECT_EQ(first_stored, 4.0f);
  Image back = read_image(dir / "d.pfm");
  EXPECT_EQ(back.pixels, disparity.pixels);
  testing::write_file(dir / "bad.pfm", "P6\n1 1\n255\nxyz");
  EXPECT_THROW(read_image(dir / "bad.pfm"), InputError);
  testing::write_file(dir / "short.pfm", "Pf\n4 4\n-1.0\nabc");
  EXPECT_THROW(read_image(dir / "short.pfm"), InputError);
  // A fuzzing finding: a 15-byte file whose header declares 27776x7651 colour pixels used to be
  // allocated (2.5 GB, zeroed) before the first row was found missing. The message names the
  // size the header declares.
  testing::write_file(dir / "huge.pfm", "PF\n27776 7651\n1");
  try {
    read_image(dir / "huge.pfm");
    ADD_FAILURE() << "a truncated PFM was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("27776x7651 pixels"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace countershade
