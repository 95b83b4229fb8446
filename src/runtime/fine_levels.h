#pragma once
// How a 16-bit stimulus reaches a framebuffer with fewer levels per channel. The definitions here
// are the reference the GPU path is tested against: the shader in deep_stimulus.cpp computes the
// same integers (its GLSL is kFineLevelsGlsl below, kept next to the C++ it mirrors).
//
//   ten-bit  a 10-bit framebuffer, each channel at its nearest 10-bit level;
//   dither   8 bits with a seeded spatio-temporal dither: each frame a pixel shows one of the two
//            8-bit levels around its 16-bit value, chosen so that over any 64 consecutive frames
//            the mean is within 1/64 of a level of the value;
//   pseudo-grey  8 bits with bit stealing (Tyler 1992) for achromatic sets: between two grey
//            levels, six steps made by raising one or two of R, G and B by one level, which the
//            guns' unequal luminances place at about 0.11, 0.30, 0.41, 0.59, 0.70 and 0.89 of the
//            step (1786 distinct levels in all);
//   8-bit    an 8-bit set shown as it is.

#include <cstdint>
#include <optional>
#include <string>

namespace countershade::runtime {

enum class OutputPath { eight_bit, ten_bit, dither, pseudo_grey };

const char* output_path_name(OutputPath path);

// What the user may ask for: a path, or "auto" (ten-bit where a read-back confirms it, else
// dither).
struct OutputPathChoice {
  bool automatic = true;
  OutputPath path = OutputPath::dither;
  // Whether the 10-bit framebuffer is asked for, and its read-back checked.
  bool may_use_ten_bit() const { return automatic || path == OutputPath::ten_bit; }
};
// Parses "auto", "ten-bit", "dither" or "pseudo-grey"; nothing for anything else.
std::optional<OutputPathChoice> parse_output_path(const std::string& text);

// The nearest 10-bit level of a 16-bit value: round(v · 1023 / 65535).
inline uint32_t ten_bit_level(uint32_t v16) { return (v16 * 1023u + 32767u) / 65535u; }

// The dither's threshold for image pixel (x, y) at a frame, in [0, 65535). A pixel's 64 strata are
// visited once in every 64 consecutive frames (stride 37, coprime with 64), at a random phase and
// with a random offset inside the stratum, both from a hash of the pixel and the seed.
uint32_t dither_threshold(uint32_t x, uint32_t y, uint32_t frame, uint32_t seed);
// The part of the threshold's hash that depends on the seed alone (the GLSL dither_threshold takes
// it in place of the seed, computed once per frame).
uint32_t dither_seed_mix(uint32_t seed);

// The 8-bit level the dither shows: floor((v · 255 + threshold) / 65535). Its mean over thresholds
// spread evenly over [0, 65535) is v · 255 / 65535, the 16-bit value in 8-bit levels.
inline uint32_t dither_level(uint32_t v16, uint32_t threshold) {
  return (v16 * 255u + threshold) / 65535u;
}

// Bit stealing with Psychtoolbox's CreatePseudoGrayLUT table: a 12-bit index over the sixteenths of
// a grey level, its top 8 bits the grey level in all three channels, and its low 4 bits (the slot)
// choosing which channels go one level up. Bit `slot` of each mask says whether that channel does.
inline constexpr uint32_t kPseudoGreyRed = 0xC1E0u;    // slots 5-8, 14, 15
inline constexpr uint32_t kPseudoGreyGreen = 0xFE00u;  // slots 9-15
inline constexpr uint32_t kPseudoGreyBlue = 0x399Cu;   // slots 2-4, 7, 8, 11-13

// The index of a 16-bit grey value: round(v · 255 · 16 / 65535), so that each 8-bit level is its
// own slot 0 and white is 255 in every channel.
inline uint32_t pseudo_grey_index(uint32_t v16) { return (v16 * 4080u + 32767u) / 65535u; }

// How far apart a pixel's R, G and B may be for pseudo-grey to show it as one grey: 1/16 of an
// 8-bit level (renders of grey scenes differ by a code here and there after colour conversions).
inline constexpr uint32_t kAchromaticSpread = 16;

// The grey pseudo-grey shows for a pixel: the rounded mean of its three codes.
inline uint32_t pseudo_grey_value(uint32_t r, uint32_t g, uint32_t b) {
  return (r + g + b + 1u) / 3u;
}

// The 8-bit level of a channel (its mask above) for a 16-bit grey value.
inline uint32_t pseudo_grey_level(uint32_t v16, uint32_t mask) {
  const uint32_t i = pseudo_grey_index(v16);
  const uint32_t level = (i >> 4) + ((mask >> (i & 15u)) & 1u);
  return level < 255u ? level : 255u;
}

// The functions above in GLSL 3.30 (uint arithmetic wraps as C++'s uint32_t does).
extern const char* const kFineLevelsGlsl;

}  // namespace countershade::runtime
