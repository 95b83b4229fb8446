#pragma once
// The vector kernels of the lightness-only composition (enhance/lightness.h) and of the CIELAB
// conversion of display pixels: AVX-512, AVX2 and plain x86-64 code paths, chosen at run time, that
// give the same bits as the scalar functions of core/color.h. The rules (what Δ is, which pixels
// keep their values) live in enhance/lightness; these only compute.

#include <cstddef>
#include <cstdint>
#include <optional>

#include "core/code_quantizer.h"
#include "core/color.h"

namespace countershade {

// The display code values of pixels whose L* changes by Δ (a* and b* scaled by L'/L), quantised
// as one quantizer does, through the widest path the processor allows.
class LightnessComposer {
 public:
  LightnessComposer(const CodeQuantizer& quantizer, int bits);

  // `count` ≤ 64 pixels: `lab` and `source` (their code values) with their Δ in `delta`; writes
  // `target` (RGB code values). Pixels with Δ = 0 keep their source values exactly. Eight at a time
  // where AVX-512 allows, then four at a time through the quantizer's table, then one by one.
  // Returns the number of clipped pixels (the target L* or a channel outside its range).
  size_t compose(const Lab* lab, const float* source, const double* delta, size_t count,
                 float* target) const;

 private:
  const CodeQuantizer& quantizer_;
  std::optional<CodeQuantizer::Table> table_;
  double inverse_levels_;
  bool eight_;
};

// CIELAB of `count` linear RGB pixels given as three planes, and optionally their L* as floats.
// Streaming stores where `out` is 16-byte aligned: the caller fences (_mm_sfence) before reading.
void linear_to_lab_block(const double* r, const double* g, const double* b, size_t count, Lab* out,
                         float* lightness);
// L* alone of `count` linear RGB pixels: the values linear_to_lab_block gives.
void linear_to_lightness_block(const double* r, const double* g, const double* b, size_t count,
                               double* lightness);

// The codes (code / levels) of n values, and whether every value is exactly its code's value.
bool exact_codes(const float* values, size_t n, float levels, int32_t* code);

// The table's values of the codes of `count` RGB pixels (code[3k + channel]), one plane per
// channel.
void gather_planes(const int32_t* __restrict code, size_t count, const double* __restrict table,
                   double* __restrict r, double* __restrict g, double* __restrict b);

}  // namespace countershade
