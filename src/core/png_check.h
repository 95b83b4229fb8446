#pragma once
// The chunk structure of a PNG file, checked before a decoder sees it. libpng prints its own
// "libpng error: …" line to stderr before any caller can report the error, so a truncated or
// damaged file is refused here with one line of ours instead.

#include <filesystem>
#include <string_view>

namespace countershade {

// True when `bytes` start with the 8-byte PNG signature.
bool has_png_signature(std::string_view bytes);

// Walks the chunks of a PNG file held in `bytes`: each chunk lies inside the file and its CRC
// matches, IHDR comes first, there is image data, and IEND ends the file. Throws InputError
// naming `path`, the chunk and its byte offset otherwise.
void check_png_chunks(const std::filesystem::path& path, std::string_view bytes);

}  // namespace countershade
