#pragma once
// Lossless videos of frame sequences, for sharing a moving stimulus in one file: FFV1 (version 3,
// 8-bit RGB) in Matroska, written bit-exact so the same frames always give the same bytes. The
// frames stay the reference; every video is decoded again and compared with them pixel for pixel.

#include <cstdint>
#include <filesystem>
#include <vector>

#include "core/image.h"

namespace countershade {

// Writes the 8-bit RGB frames (all of one size) at `fps`, atomically, then decodes the file and
// throws std::runtime_error unless every pixel of every frame comes back unchanged.
void write_lossless_video(const std::filesystem::path& output, const std::vector<Image>& frames,
                          double fps);

// Decodes a video into RGB images (code values in [0, 1], as read_image gives them).
std::vector<Image> read_video_frames(const std::filesystem::path& video);

}  // namespace countershade
