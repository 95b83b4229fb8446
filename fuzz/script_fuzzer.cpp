// Fuzzes the adjustment app's input script reader (adjust/input_script): any bytes as --script.
#include "fuzz/fuzz_input.h"
#include "runtime/key_script.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = countershade::fuzz::write_input(data, size, "keys.txt");
  return countershade::fuzz::expect_clean_refusal(
      [&] { countershade::runtime::parse_key_script(path); });
}
