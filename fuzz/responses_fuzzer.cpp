// Fuzzes the responses CSV reader (analysis/responses): any bytes as a session CSV.
#include "analysis/responses.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = countershade::fuzz::write_input(data, size, "session.csv");
  return countershade::fuzz::expect_clean_refusal(
      [&] { countershade::analysis::read_responses(path); });
}
