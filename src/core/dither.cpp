#include "core/dither.h"

#include <algorithm>

#include "core/random.h"

namespace countershade {
namespace {

// k's six bits in reverse: consecutive frames jump between the halves, quarters, … of [0, 1).
constexpr uint32_t reverse6(uint32_t k) {
  uint32_t r = 0;
  for (int b = 0; b < 6; ++b) r |= ((k >> b) & 1u) << (5 - b);
  return r;
}

}  // namespace

void dither_to_8_bits(std::span<const uint16_t> values, uint64_t seed, uint64_t frame, std::span<uint8_t> out) {
  const uint64_t key = hash_combine(seed, 0x6469746865720000ull);  // "dither"
  for (size_t i = 0; i < values.size(); ++i) {
    const uint64_t h = hash_combine(key, i);
    const uint32_t start = uint32_t(h & 63u);
    const double offset = double(h >> 11) * 0x1p-53;  // within the stratum, in [0, 1)
    const double threshold = (reverse6(uint32_t((frame + start) & 63u)) + offset) / kDitherPeriod;
    // The exact level of the 16-bit value on the 8-bit scale: v·255/65535 = v/257.
    const double level = double(values[i]) / 257.0;
    out[i] = uint8_t(std::min(255.0, level + threshold));
  }
}

}  // namespace countershade
