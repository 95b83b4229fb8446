#include "core/isa.h"

#include <atomic>

namespace countershade {
namespace {

std::atomic<bool> avx512_allowed{true};

bool processor_has_avx512() {
#if defined(COUNTERSHADE_WITHOUT_AVX512)
  return false;
#else
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
         __builtin_cpu_supports("bmi") && __builtin_cpu_supports("bmi2") &&
         __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") &&
         __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw") &&
         __builtin_cpu_supports("avx512vl");
#endif
}

}  // namespace

bool has_avx512() {
  static const bool processor = processor_has_avx512();
  return processor && avx512_allowed.load(std::memory_order_relaxed);
}

void allow_avx512(bool allow) { avx512_allowed = allow; }

}  // namespace countershade
