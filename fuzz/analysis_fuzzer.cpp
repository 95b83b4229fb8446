// Fuzzes the whole analysis behind the responses reader: any bytes as a session CSV, read, then
// analysed and written out (tables, figures, report) as `countershade analyze` does. The reader
// alone (the responses harness) let through answers whose statistics overflowed and crashed.
// The input's size picks the options, so every seed is a plain CSV: its parity the JND
// normalisation, the next digit in base 3 the threshold model, the next two bits a small bootstrap
// (one in four).
#include "analysis/analysis.h"
#include "analysis/report.h"
#include "analysis/responses.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace countershade;
  const auto path = fuzz::write_input(data, size, "session.csv");
  return fuzz::expect_clean_refusal([&] {
    const std::vector<analysis::Response> responses = analysis::read_responses(path);
    analysis::AnalysisOptions options;
    options.normalization =
        size % 2 ? analysis::JndNormalization::group : analysis::JndNormalization::subject;
    options.model = (size / 2) % 3 == 0   ? analysis::ThresholdModel::log_normal
                    : (size / 2) % 3 == 1 ? analysis::ThresholdModel::weibull
                                          : analysis::ThresholdModel::logistic;
    options.bootstrap = (size / 6) % 4 == 1 ? 2 : 0;  // slow: a quarter of the inputs
    const std::vector<analysis::BlockResults> blocks = analysis::analyze(responses, options);
    std::filesystem::create_directories(fuzz::input_folder() / "report");
    analysis::write_outputs(blocks, fuzz::input_folder() / "report", true);
  });
}
