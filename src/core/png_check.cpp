#include "core/png_check.h"

#include <zlib.h>

#include <cstdint>
#include <string>

#include "core/error.h"

namespace countershade {
namespace {

constexpr std::string_view kSignature("\x89PNG\r\n\x1a\n", 8);

uint32_t big_endian(std::string_view bytes, size_t at) {
  const auto* b = reinterpret_cast<const unsigned char*>(bytes.data() + at);
  return uint32_t(b[0]) << 24 | uint32_t(b[1]) << 16 | uint32_t(b[2]) << 8 | uint32_t(b[3]);
}

// A chunk type for messages: four letters, or its bytes in hex when they are not letters.
std::string chunk_name(std::string_view type) {
  for (char c : type)
    if (!((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'))) return "with a non-letter type";
  return std::string(type);
}

}  // namespace

bool has_png_signature(std::string_view bytes) {
  return bytes.substr(0, kSignature.size()) == kSignature;
}

void check_png_chunks(const std::filesystem::path& path, std::string_view bytes) {
  const std::string file = path.string();
  if (!has_png_signature(bytes)) throw_input_error(file, "not a PNG file (no PNG signature)");
  size_t at = kSignature.size();
  bool image_data = false;
  for (int index = 0;; ++index) {
    const std::string where = " at byte " + std::to_string(at);
    if (bytes.size() - at < 12)
      throw_input_error(
          file, "truncated PNG: the file ends" + where + (index ? ", before the IEND chunk" : ""));
    const uint32_t length = big_endian(bytes, at);
    const std::string_view type = bytes.substr(at + 4, 4);
    const std::string name = "chunk " + chunk_name(type) + where;
    if (length > 0x7fffffffu || bytes.size() - at - 12 < length)
      throw_input_error(file, "truncated PNG: " + name + " claims " + std::to_string(length) +
                                  " bytes, the file has " + std::to_string(bytes.size() - at - 12) +
                                  " left");
    const uint32_t stored = big_endian(bytes, at + 8 + length);
    const auto* start = reinterpret_cast<const Bytef*>(bytes.data() + at + 4);
    if (uint32_t(crc32(crc32(0L, Z_NULL, 0), start, uInt(length + 4))) != stored)
      throw_input_error(file, "damaged PNG: " + name + " fails its CRC check");
    if (index == 0 && type != "IHDR")
      throw_input_error(file, "damaged PNG: the first chunk is not IHDR");
    image_data |= type == "IDAT";
    at += 12 + length;
    if (type == "IEND") break;
  }
  if (!image_data) throw_input_error(file, "damaged PNG: no image data (IDAT chunk)");
}

}  // namespace countershade
