#pragma once
// The lossless videos of a set's sequences (experiment key "video"): SEQUENCE.mkv beside every
// sequence folder, made from the frames as written and checked to decode back to them.

#include <filesystem>

#include "formats/manifest.h"

namespace countershade {

// Writes the videos of every sequence in `manifest` (a complete set in `dir`) and lists them in
// manifest.videos, in folder order.
void write_sequence_videos(const std::filesystem::path& dir, Manifest& manifest, int threads);

}  // namespace countershade
