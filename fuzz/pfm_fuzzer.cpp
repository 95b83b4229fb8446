// Fuzzes the PFM reader (core/image): any bytes as a .pfm image.
#include "core/image.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = countershade::fuzz::write_input(data, size, "image.pfm");
  return countershade::fuzz::expect_clean_refusal([&] { countershade::read_image(path); });
}
