// Fuzzes PNG decoding: any bytes as a .png image, through both ways a program reads one.
// read_image checks the chunks first (core/png_check.h), then decodes with the libpng codec or,
// for what that declines, OpenImageIO; the apps' stimulus decoder (runtime/image_decode.h) goes
// to the codec directly, so libpng's own errors are all that stands between it and bad bytes.
#include <algorithm>

#include "core/image.h"
#include "fuzz/fuzz_input.h"
#include "runtime/image_decode.h"

namespace {

// The header's width or height (big-endian at bytes 16 and 20), so that the stimulus decoder
// gets past its comparison with the manifest's size; 0 when the input is too short.
int header_number(const uint8_t* data, size_t size, size_t at) {
  if (size < at + 4) return 0;
  const uint32_t v = uint32_t(data[at]) << 24 | uint32_t(data[at + 1]) << 16 |
                     uint32_t(data[at + 2]) << 8 | uint32_t(data[at + 3]);
  return int(std::min<uint32_t>(v, 1u << 30));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace countershade;
  const auto path = fuzz::write_input(data, size, "image.png");
  fuzz::expect_clean_refusal([&] { read_image(path); });
  const runtime::StimulusImage stimulus{path, "image.png", "", header_number(data, size, 16),
                                        header_number(data, size, 20)};
  fuzz::expect_clean_refusal([&] { runtime::decode_rgba(stimulus); });
  return fuzz::expect_clean_refusal([&] { runtime::decode_rgba16(stimulus); });
}
