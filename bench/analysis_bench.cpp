// The whole analysis of 200 simulated subjects × the full design (4 scenes × 3 σ × 3 questions,
// 7,200 answers) with B = 1000 bootstrap resamples per fit (36 fits), on all cores.
//   build/bin/countershade_bench --benchmark_filter=Analysis

#include <benchmark/benchmark.h>

#include "analysis/analysis.h"
#include "analysis/simulate.h"

namespace countershade::analysis {
namespace {

void BM_AnalysisFullDesign(benchmark::State& state) {
  SimulationDesign design;
  design.subjects = 200;
  auto responses = simulate_responses(design);
  AnalysisOptions options;
  options.bootstrap = int(state.range(0));
  for (auto _ : state) {
    auto results = analyze(responses, options);
    benchmark::DoNotOptimize(results.data());
  }
  state.counters["answers"] = double(responses.size());
}
BENCHMARK(BM_AnalysisFullDesign)
    ->Arg(0)
    ->Arg(1000)
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

}  // namespace
}  // namespace countershade::analysis
