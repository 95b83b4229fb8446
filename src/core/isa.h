#pragma once
// Clones of hot loops for the instruction sets of x86-64 processors, the best one chosen at run
// time. Every clone gives the same bits (no fused multiply-adds anywhere, CMakeLists.txt), so the
// choice changes only the speed.
//
// A build with -DCOUNTERSHADE_WITHOUT_AVX512=ON leaves the AVX-512 code out, so that a machine
// with AVX-512 runs what processors without it run: benchmarks of that build measure the AVX2 path
// instead of estimating it (docs/performance.md).

#include <cstdint>

namespace countershade {

// Whether the AVX-512 functions below may run: the processor has AVX-512 (F, CD, DQ, BW, VL), this
// is not a COUNTERSHADE_WITHOUT_AVX512 build, and allow_avx512 did not turn them off.
bool has_avx512();
// Turns the AVX-512 functions off (false) or on again where the processor has them (true, the
// default). Both ways give the same bits; tests and benchmarks compare the two paths on one
// machine.
void allow_avx512(bool allow);

// Lanes of doubles (and their 64-bit integers) for loops written once for any lane count: eight
// for the AVX-512 function, four for the others. Vectors wider than the processor's registers cost
// 2.5-5 times as much: GCC moves their lanes through scalar code in places.
using NarrowLanes = double __attribute__((vector_size(32)));
using NarrowLaneBits = int64_t __attribute__((vector_size(32)));
#if defined(__clang__)
// clang refuses 512-bit vectors as arguments of the (always-inline) helpers, so its builds
// (fuzzing, sanitizers) take four lanes throughout; the values are the same.
using WideLanes = NarrowLanes;
using WideLaneBits = NarrowLaneBits;
#else
using WideLanes = double __attribute__((vector_size(64)));
using WideLaneBits = int64_t __attribute__((vector_size(64)));
#endif

}  // namespace countershade

// A function for processors with AVX-512, called only where has_avx512().
#define COUNTERSHADE_AVX512_FUNCTION __attribute__((target("arch=x86-64-v4")))
// Clones of a function for processors without AVX-512: AVX2 (x86-64-v3) and the x86-64 baseline.
#define COUNTERSHADE_AVX2_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
// Clones for every level, for loops the compiler vectorises itself (no explicit lanes).
#if defined(COUNTERSHADE_WITHOUT_AVX512)
#define COUNTERSHADE_CLONES COUNTERSHADE_AVX2_CLONES
#else
#define COUNTERSHADE_CLONES \
  __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#endif
