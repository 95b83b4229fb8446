#pragma once
// Lossless FFV1 videos through libavcodec, behind a small interface in a library of its own
// (libcountershade_video_codec.so): FFmpeg brings about 130 shared libraries, loaded only by the
// commands that write or read a video (core/plugin_library.h). stimuli/lossless_video.h is what
// the program calls.

#include <cstdint>
#include <string>
#include <vector>

namespace countershade::codecs {

// One frame of 8-bit RGB, interleaved, rows top to bottom.
struct RgbFrame {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;
};

class VideoCodec {
 public:
  virtual ~VideoCodec() = default;
  // FFV1 (version 3, 8-bit RGB) in Matroska, the same bytes for the same frames; "" or why not.
  virtual std::string write_ffv1(const std::string& path, const std::vector<RgbFrame>& frames,
                                 double fps) const = 0;
  // Every frame of the file's video stream as 8-bit RGB; "" or why not.
  virtual std::string read(const std::string& path, std::vector<RgbFrame>& frames) const = 0;
};

}  // namespace countershade::codecs
