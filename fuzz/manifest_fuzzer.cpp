// Fuzzes the stimulus-set manifest reader (formats/manifest): any bytes as a manifest.json.
#include "formats/manifest.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = countershade::fuzz::write_input(data, size, "manifest.json");
  return countershade::fuzz::expect_clean_refusal([&] { countershade::read_manifest(path); });
}
