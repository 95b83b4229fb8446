// The benchmark runner: the process is set up as the countershade binary sets itself up.

#include <benchmark/benchmark.h>

#include "core/allocator.h"

int main(int argc, char** argv) {
  countershade::keep_freed_buffers_for_reuse();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
