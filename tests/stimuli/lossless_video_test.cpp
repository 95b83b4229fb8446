// Lossless videos: every pixel of every frame decodes back unchanged, the same frames give the
// same bytes, and a file that is not a video is refused.

#include "stimuli/lossless_video.h"

#include <gtest/gtest.h>

#include <algorithm>
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

// Every name in `dir`, hidden ones included, sorted: a temporary file left behind shows.
std::vector<std::string> names_in(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
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
  EXPECT_EQ(names_in(dir.path()), (std::vector<std::string>{"a.mkv", "b.mkv"}));
}

// Frames of differing sizes are refused, naming the first that differs, and nothing is written.
TEST(LosslessVideo, FramesOfAnotherSizeAreRefusedAndNothingIsWritten) {
  testing::TempDir dir;
  std::vector<Image> frames = noise_frames(3, 37, 23);
  frames.push_back(noise_frames(1, 20, 10).front());
  try {
    write_lossless_video(dir / "c.mkv", frames, 30);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("frame 4 is 20x10, the first 37x23"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(names_in(dir.path()), std::vector<std::string>{});
}

TEST(LosslessVideo, AFileThatIsNotAVideoIsRefused) {
  testing::TempDir dir;
  testing::write_file(dir / "not.mkv", "plain text, not Matroska");
  EXPECT_THROW(read_video_frames(dir / "not.mkv"), std::runtime_error);
  EXPECT_THROW(write_lossless_video(dir / "none.mkv", {}, 30), std::runtime_error);
}

}  // namespace
}  // namespace countershade
