// Forced-choice fits of 200 simulated subjects × 12 conditions (8 levels × 40 trials each,
// 768,000 trials): 2,412 Weibull fits (per subject and pooled) with 1,000 bootstrap refits each.
//   build/bin/countershade_bench --benchmark_filter=Psychometric

#include <benchmark/benchmark.h>

#include "analysis/forced_choice_analysis.h"
#include "analysis/forced_choice_simulation.h"

namespace countershade::analysis {
namespace {

ForcedChoiceDesign study_design() {
  ForcedChoiceDesign design;
  const char* scenes[] = {"chamfer", "dice", "keys", "feet"};
  const double sigmas[] = {0.01, 0.02, 0.04};
  for (const char* scene : scenes)
    for (double sigma : sigmas) {
      const double alpha = 0.2 + 4 * sigma;
      std::vector<double> levels;
      for (int i = 1; i <= 8; ++i) levels.push_back(alpha * 0.3 * i);
      design.conditions.push_back({scene, sigma, alpha, 3.0, levels});
    }
  design.subjects = 200;
  design.subject_sd = 0.1;
  design.lapse = 0.01;
  return design;
}

void BM_PsychometricFitsWithBootstrap(benchmark::State& state) {
  const auto trials = simulate_forced_choice(study_design());
  ForcedChoiceOptions options;
  options.bootstrap = int(state.range(0));
  size_t fits = 0;
  for (auto _ : state) {
    const ForcedChoiceResults results = analyze_forced_choice(trials, options);
    fits = results.rows.size();
    benchmark::DoNotOptimize(results.rows.data());
  }
  state.counters["fits"] = double(fits);
  state.counters["trials"] = double(trials.size());
}
BENCHMARK(BM_PsychometricFitsWithBootstrap)
    ->Arg(0)
    ->Arg(1000)
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

}  // namespace
}  // namespace countershade::analysis
