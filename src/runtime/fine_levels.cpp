#include "runtime/fine_levels.h"

namespace countershade::runtime {

const char* output_path_name(OutputPath path) {
  switch (path) {
    case OutputPath::eight_bit:
      return "8-bit";
    case OutputPath::ten_bit:
      return "ten-bit";
    case OutputPath::dither:
      return "dither";
    case OutputPath::pseudo_grey:
      return "pseudo-grey";
  }
  return "?";
}

std::optional<OutputPathChoice> parse_output_path(const std::string& text) {
  if (text == "auto") return OutputPathChoice{};
  if (text == "ten-bit") return OutputPathChoice{false, OutputPath::ten_bit};
  if (text == "dither") return OutputPathChoice{false, OutputPath::dither};
  if (text == "pseudo-grey") return OutputPathChoice{false, OutputPath::pseudo_grey};
  return std::nullopt;
}

namespace {

// A 32-bit integer hash with good avalanche (the "lowbias32" constants), cheap on a GPU.
uint32_t mix(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

}  // namespace

uint32_t dither_seed_mix(uint32_t seed) { return mix(seed); }

uint32_t dither_threshold(uint32_t x, uint32_t y, uint32_t frame, uint32_t seed) {
  const uint32_t h = mix(x + mix(y + dither_seed_mix(seed)));
  const uint32_t stratum = ((h >> 26) + frame * 37u) & 63u;
  const uint32_t position = (stratum << 10) | (h & 1023u);  // 0 .. 65535
  return (position * 65535u) >> 16;                         // 0 .. 65534
}

const char* const kFineLevelsGlsl = R"(
uint mix_bits(uint x) {
  x ^= x >> 16; x *= 0x7feb352du; x ^= x >> 15; x *= 0x846ca68bu; x ^= x >> 16;
  return x;
}
uint dither_threshold(uint x, uint y, uint frame, uint seed_mix) {  // seed_mix: dither_seed_mix(seed)
  uint h = mix_bits(x + mix_bits(y + seed_mix));
  uint stratum = ((h >> 26) + frame * 37u) & 63u;
  uint position = (stratum << 10) | (h & 1023u);
  return (position * 65535u) >> 16;
}
// n / 65535 without a division, which a software rasteriser runs lane by lane; exact for every n
// the functions below pass (every 16-bit value is checked against the C++ in the tests).
uvec3 over_65535(uvec3 n) { return (n + 1u + (n >> 16)) >> 16; }
uvec3 ten_bit_level(uvec3 v) { return over_65535(v * 1023u + 32767u); }
uvec3 dither_level(uvec3 v, uint threshold) { return over_65535(v * 255u + threshold); }
uvec3 pseudo_grey_levels(uint v) {
  uint i = over_65535(uvec3(v * 4080u + 32767u)).x;
  uvec3 boost = (uvec3(0xC1E0u, 0xFE00u, 0x399Cu) >> (i & 15u)) & 1u;
  return min(uvec3(i >> 4) + boost, uvec3(255u));
}
)";

}  // namespace countershade::runtime
