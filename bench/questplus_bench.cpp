// QUEST+ on the grid of Watson's (2017) largest example, 10^6 parameter points (100 thresholds ×
// 50 slopes × 20 lapse rates × 10 guess rates) and 50 stimuli: building the tables, choosing the
// next stimulus (the expected entropy of every stimulus), and one answer's update.
//   build/bin/countershade_bench --benchmark_filter=QuestPlus
// The process's peak memory (ru_maxrss) is reported as the counter peak_MiB.

#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include "procedures/questplus.h"

namespace countershade::procedures {
namespace {

std::vector<double> steps(double from, double to, size_t n) {
  std::vector<double> out;
  for (size_t i = 0; i < n; ++i) out.push_back(from + (to - from) * double(i) / double(n - 1));
  return out;
}

QuestPlusDefinition large_definition() {
  QuestPlusDefinition d;
  d.shape = PsychometricShape::weibull;
  d.scale = StimulusScale::log10;
  d.stimuli = steps(-3, 0, 50);
  d.grids = {steps(-3, 0, 100), steps(1, 6, 50), steps(0, 0.5, 10), steps(0, 0.05, 20)};
  return d;
}

double peak_mib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024;
}

void BM_QuestPlusTables(benchmark::State& state) {
  for (auto _ : state) {
    QuestPlus quest(large_definition());
    benchmark::DoNotOptimize(quest.entropy());
  }
  state.counters["peak_MiB"] = peak_mib();
}

void BM_QuestPlusNextStimulus(benchmark::State& state) {
  QuestPlus quest(large_definition());
  quest.update(20, true);  // a posterior that is no longer the prior
  quest.update(10, false);
  for (auto _ : state) benchmark::DoNotOptimize(quest.next());
  state.counters["peak_MiB"] = peak_mib();
}

void BM_QuestPlusUpdate(benchmark::State& state) {
  QuestPlus quest(large_definition());
  bool correct = true;
  for (auto _ : state) {
    quest.update(25, correct);
    correct = !correct;
  }
}

BENCHMARK(BM_QuestPlusTables)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_QuestPlusNextStimulus)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_QuestPlusUpdate)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace countershade::procedures
