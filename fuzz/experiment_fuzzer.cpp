// Fuzzes the experiment JSON reader (stimuli/experiment): any bytes as an experiment file, next to
// a scene.json it may use.
#include "fuzz/fuzz_input.h"
#include "stimuli/experiment.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const bool support =
      (countershade::fuzz::write_support_file("scene.json", countershade::fuzz::kSupportScene),
       true);
  (void)support;
  const auto path = countershade::fuzz::write_input(data, size, "experiment.json");
  return countershade::fuzz::expect_clean_refusal([&] { countershade::load_experiment(path); });
}
