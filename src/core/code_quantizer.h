#pragma once
// Display code values from linear values, fast and exact: the same integer code as
// quantize(float(encoding.encode(x)), bits), found through thresholds computed once per
// encoding and bit depth instead of a pow() per channel. A code k is given to every linear value
// at or above threshold k; a small table indexed by the value's binary exponent and top mantissa
// bits holds at most one threshold per bucket, so a lookup is one load and one comparison.

#include <cstdint>
#include <vector>

#include "core/display.h"

namespace countershade {

// code / levels as a float, computed as a product in double: for every code of up to 16 bits the
// same float as the division float(code) / levels (tested for all), and cheaper in vector loops.
inline float code_fraction(uint32_t code, double inverse_levels) {
  return float(double(int32_t(code)) * inverse_levels);
}

// A pixel's three codes (each of up to 16 bits) as one key, for caches keyed by a pixel's codes.
inline uint64_t code_triple_key(uint32_t r, uint32_t g, uint32_t b) {
  return uint64_t(r) | uint64_t(g) << 16 | uint64_t(b) << 32;
}

class CodeQuantizer {
 public:
  CodeQuantizer(const DisplayEncoding& encoding, int bits);

  // The code of a linear value in [0,1] (clamped; NaN is 0).
  uint32_t code(double linear) const;
  // The same code as a value in [0,1] (code / (2^bits − 1)).
  float value(double linear) const { return float(code(linear)) / levels_; }
  int bits() const { return bits_; }
  bool uses_table() const { return mantissa_bits_ > 0; }

  // The quantizer of an encoding and bit depth, built once per process (building one for 16
  // bits takes a while) and shared.
  static const CodeQuantizer& shared(const DisplayEncoding& encoding, int bits);

  // The reference: what the quantizer must reproduce.
  uint32_t exact_code(double linear) const;

  // The table, for loops that look up many values at once (uses_table() only). For x in [0,1]:
  //   b = clamp((bits(x) >> shift) − offset, 0, last),
  //   code = bucket[b].below + (x ≥ bucket[b].threshold).
  struct Bucket {
    double threshold;  // the one threshold inside the bucket, or +inf
    uint32_t below;    // the code at the bucket's start
  };
  struct Table {
    int shift = 0;
    int64_t offset = 0, last = 0;
    const Bucket* bucket = nullptr;
    // The same buckets in one word each, for vector gathers: the code at the bucket's start in
    // the top 16 bits, and the threshold's bits below `shift` (all of x's bits above them are the
    // bucket's), or kNoThreshold. For a bucket b reached without clamping:
    //   code = (packed[b] >> 48) + ((bits(x) & (2^shift − 1)) ≥ (packed[b] & kLowBits)).
    const uint64_t* packed = nullptr;
  };
  static constexpr uint64_t kLowBits = (uint64_t(1) << 48) - 1;
  static constexpr uint64_t kNoThreshold = uint64_t(1) << 47;  // above the low bits of any x
  Table table() const;

 private:
  uint32_t search(double linear) const;  // binary search over all thresholds (no table)
  bool build_table(int mantissa_bits);

  DisplayEncoding encoding_;
  int bits_;
  float levels_;
  std::vector<double>
      thresholds_;  // [k]: the smallest linear value whose code is at least k (k ≥ 1)
  uint32_t code_at_zero_ = 0, code_at_one_ = 0;
  int mantissa_bits_ = 0;         // 0: no table, binary search
  std::vector<Bucket> buckets_;   // then one bucket for x = 1
  std::vector<uint64_t> packed_;  // the buckets as Table::packed words
};

}  // namespace countershade
