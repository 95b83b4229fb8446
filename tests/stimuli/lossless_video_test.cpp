// Lossless videos: every pixel of every frame decodes back unchanged, the same frames give the
// same bytes, and a file that is not a video is refused.

#include "stimuli/lossless_video.h"

#include <gtest/gtest.h>

#include <random>

#include "test_util.h"

namespace countershade {
namespace {

std::vector<Image> noise_frames(int count, int width, int height) {
  std::mt19937 random(11);
  std::uniform_int_distribution<int> level(0, 255);
  std::vector<Image> frames;
  for (int k = 0; k < count; ++k) {
    Image image(width, height, 3);
    for (float& v : image.pixels) v = float(level(random)) / 255.0f;
    image.at(0, 0, 0) = 0.0f;  // both ends of the range
    image.at(1, 0, 2) = 1.0f;
    frames.push_back(image);
  }
  return frames;
}

TEST(LosslessVideo, EveryPixelComesBackAndTheBytesAreReproducible) {
  testing::TempDir dir;
  const std::vector<Image> frames = noise_frames(5, 37, 23);  // odd sizes, incompressible content
  write_lossless_video(dir / "a.mkv", frames, 30);
  write_lossless_video(dir / "b.mkv", frames, 30);
  const std::vector<Image> back = read_video_frames(dir / "a.mkv");
  ASSERT_EQ(back.size(), frames.size());
  for (size_t k = 0; k < frames.size(); ++k) {
    ASSERT_EQ(back[k].width, 37);
    ASSERT_EQ(back[k].height, 23);
    long differing = 0;
    for (size_t i = 0; i < frames[k].pixels.size(); ++i)
      differing += std::lround(back[k].pixels[i] * 255) != std::lround(frames[k].pixels[i] * 255);
    EXPECT_EQ(differing, 0) << "frame " << k;
  }
  EXPECT_EQ(testing::read_file(dir / "a.mkv"), testing::read_file(dir / "b.mkv"));
  EXPECT_FALSE(std::filesystem::exists(dir / ".a.mkv.tmp"));
}

TEST(LosslessVideo, AFileThatIsNotAVideoIsRefused) {
  testing::TempDir dir;
  testing::write_file(dir / "not.mkv", "plain text, not Matroska");
  EXPECT_THROW(read_video_frames(dir / "not.mkv"), std::runtime_error);
  EXPECT_THROW(write_lossless_video(dir / "none.mkv", {}, 30), std::runtime_error);
}

}  // namespace
}  // namespace countershade
