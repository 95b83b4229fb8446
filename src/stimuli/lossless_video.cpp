#include "stimuli/lossless_video.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "codecs/video_codec.h"
#include "core/atomic_file.h"
#include "core/plugin_library.h"

namespace countershade {
namespace fs = std::filesystem;
namespace {

const codecs::VideoCodec& video_codec() { return plugin<codecs::VideoCodec>("video_codec"); }

[[noreturn]] void fail(const fs::path& file, const std::string& what) {
  throw std::runtime_error(file.string() + ": " + what);
}

uint8_t code(float value) { return uint8_t(std::lround(std::clamp(value, 0.0f, 1.0f) * 255.0f)); }

codecs::RgbFrame rgb_frame(const Image& image) {
  codecs::RgbFrame f{image.width, image.height,
                     std::vector<uint8_t>(size_t(image.width) * size_t(image.height) * 3)};
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c)
        f.rgb[(size_t(y) * size_t(image.width) + size_t(x)) * 3 + size_t(c)] =
            code(image.at(x, y, std::min(c, image.channels - 1)));
  return f;
}

Image image_of(const codecs::RgbFrame& f) {
  Image image(f.width, f.height, 3);
  for (size_t i = 0; i < f.rgb.size(); ++i) image.pixels[i] = float(f.rgb[i]) / 255.0f;
  return image;
}

std::vector<codecs::RgbFrame> decoded_frames(const fs::path& video) {
  std::vector<codecs::RgbFrame> frames;
  const std::string error = video_codec().read(video.string(), frames);
  if (!error.empty()) fail(video, error);
  return frames;
}

bool same_frames(const std::vector<codecs::RgbFrame>& a, const std::vector<codecs::RgbFrame>& b) {
  bool same = a.size() == b.size();
  for (size_t k = 0; same && k < a.size(); ++k)
    same = a[k].width == b[k].width && a[k].height == b[k].height && a[k].rgb == b[k].rgb;
  return same;
}

}  // namespace

std::vector<Image> read_video_frames(const fs::path& video) {
  std::vector<Image> frames;
  for (const codecs::RgbFrame& f : decoded_frames(video)) frames.push_back(image_of(f));
  return frames;
}

void write_lossless_video(const fs::path& output, const std::vector<Image>& frames, double fps) {
  if (frames.empty()) fail(output, "no frames");
  const auto size = [](const Image& f) {
    return std::to_string(f.width) + "x" + std::to_string(f.height);
  };
  for (size_t k = 1; k < frames.size(); ++k)
    if (size(frames[k]) != size(frames[0]))
      fail(output, "frame " + std::to_string(k + 1) + " is " + size(frames[k]) + ", the first " +
                       size(frames[0]));
  std::vector<codecs::RgbFrame> rgb;
  for (const Image& frame : frames) rgb.push_back(rgb_frame(frame));
  // The video takes its name only once it has decoded back to its frames; on any failure the
  // temporary file goes.
  write_atomically(output, [&](const fs::path& temporary) {
    const std::string error = video_codec().write_ffv1(temporary.string(), rgb, fps);
    if (!error.empty()) fail(output, error);
    if (!same_frames(decoded_frames(temporary), rgb))
      fail(output, "the video does not decode back to its frames");
  });
}

}  // namespace countershade
