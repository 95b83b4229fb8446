// Fuzzes the adjustment procedure reader (adjust/study): any bytes as a --procedure file.
#include "core/json_reader.h"
#include "fuzz/fuzz_input.h"
#include "procedures/adjustment_block.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = countershade::fuzz::write_input(data, size, "procedure.json");
  return countershade::fuzz::expect_clean_refusal([&] {
    countershade::procedures::parse_study_config(countershade::parse_json_file(path), path.string(),
                                                 "");
  });
}
