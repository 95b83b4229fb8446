// Fuzzes what `countershade serve` reads from a stranger: any bytes as a POSTed row (header and
// one row of CSV), checked against a session's plan, and as an Idempotency-Key. Bad input must end
// in a Refusal (a 4xx answer); anything else is a finding.
#include "fuzz/fuzz_input.h"
#include "serve/posted_row.h"
#include "serve/refusal.h"
#include "serve/session_plan.h"

namespace {

using countershade::serve::StudyFolder;

// A study of two conditions as export-web writes it (study.js), with the adjustment's columns.
const StudyFolder& fuzz_study() {
  static const StudyFolder folder = [] {
    StudyFolder f;
    f.page = nlohmann::json::parse(R"({"format": "countershade-web-study", "seed": "5",
      "set": {"sha256": "ab"}, "app_version": "0.1.0", "repetitions": 2, "side": "counterbalanced",
      "start": "random", "practice_trials": 1, "practice_conditions": [0],
      "lambda_step": "0.5", "lambda_grid": {"min": 0, "step": 0.5},
      "conditions": [
        {"scene": "cube", "method": "usm3d", "sigma": "0.1", "sigma_value": 0.1,
         "grid": ["0", "0.5", "1"], "lambda_max": "1"},
        {"scene": "cube", "method": "usm2d", "sigma": "2", "sigma_value": 2,
         "grid": ["0", "0.5"], "lambda_max": "0.5"}]})");
    f.set_sha256 = "ab";
    f.app_version = "0.1.0";
    f.columns = countershade::serve::posted_columns(f.kind);
    return f;
  }();
  return folder;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace countershade::serve;
  const std::string text(reinterpret_cast<const char*>(data), size);
  static const SessionPlan plan(fuzz_study(), "P01", 1);
  try {
    plan.check(parse_posted_row(text, fuzz_study().columns));
  } catch (const Refusal&) {
  }
  try {
    row_index_of_key(text, "countershade:ab:P01:1");
  } catch (const Refusal&) {
  }
  return 0;
}
