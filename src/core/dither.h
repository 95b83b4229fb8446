#pragma once
// Spatio-temporal dithering of 16-bit stimuli to an 8-bit display (docs/display.md, "More than 8
// bits"). Each frame rounds every value up or down by its own threshold: the thresholds of a pixel
// run through the 64 strata of [0, 1) in bit-reversed order, from a start and an offset within the
// stratum that the seed gives each pixel, so neighbouring pixels and consecutive frames differ.
// Over any 64 consecutive frames a pixel's mean level is within 1/64 of a level of its 16-bit
// value (Hermite's identity: Σ_k ⌊x + (k + r)/64⌋ = ⌊64x + r⌋), where one fixed random threshold
// per frame would leave it about 1/16 of a level away.

#include <cstddef>
#include <cstdint>
#include <span>

namespace countershade {

inline constexpr int kDitherPeriod = 64;  // frames over which the mean is exact to 1/64 level

// The 8-bit values of frame `frame` of 16-bit code values (0 … 65535), from `seed`: a pure function
// of (seed, frame, index, value), so the frames can be made again from the seed.
void dither_to_8_bits(std::span<const uint16_t> values, uint64_t seed, uint64_t frame, std::span<uint8_t> out);

}  // namespace countershade
