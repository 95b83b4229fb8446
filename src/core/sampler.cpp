#include "core/sampler.h"

namespace countershade {
namespace {

uint32_t reverse_bits(uint32_t x) {
  x = __builtin_bswap32(x);
  x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  return ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
}

// Laine and Karras' permutation: every bit depends only on itself and the bits below it, so on
// bit-reversed values it is a nested uniform (Owen) scramble.
uint32_t laine_karras(uint32_t x, uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

// An Owen scramble of x: reverse(laine_karras(reverse(x))). The callers pass values already
// reversed where they can, which saves two reversals.
uint32_t owen_of_reversed(uint32_t reversed, uint32_t seed) {
  return reverse_bits(laine_karras(reversed, seed));
}

// The second Sobol dimension (generator x + 1: v_i = v_(i−1) xor (v_(i−1) >> 1)), bit-reversed,
// as XOR tables over the index's four bytes.
struct ReversedSecondDimension {
  uint32_t byte[4][256];
  constexpr ReversedSecondDimension() : byte() {
    uint32_t column[32] = {};
    column[0] = 1u;  // reverse(1 << 31)
    for (int i = 1; i < 32; ++i) column[i] = column[i - 1] ^ (column[i - 1] << 1);
    for (int b = 0; b < 4; ++b)
      for (uint32_t v = 0; v < 256; ++v) {
        uint32_t x = 0;
        for (int bit = 0; bit < 8; ++bit)
          if (v & (1u << bit)) x ^= column[8 * b + bit];
        byte[b][v] = x;
      }
  }
  uint32_t operator()(uint32_t k) const {
    return byte[0][k & 255u] ^ byte[1][(k >> 8) & 255u] ^ byte[2][(k >> 16) & 255u] ^
           byte[3][k >> 24];
  }
};
constexpr ReversedSecondDimension kReversedSecond;

double to_unit(uint32_t x) { return double(x) * 0x1p-32; }

// The shuffled index: an Owen scramble of the sample number, which keeps every aligned block of
// 2^m numbers in one aligned block.
uint32_t shuffled_index(uint32_t index, uint64_t seed) {
  return owen_of_reversed(reverse_bits(index), uint32_t(mix64(seed)));
}

}  // namespace

glm::dvec2 scrambled_sobol_2d(uint32_t index, uint64_t seed) {
  const uint32_t k = shuffled_index(index, seed);
  // Dimension 0 is the van der Corput sequence reverse(k): its reversal is k itself.
  const uint32_t x = owen_of_reversed(k, uint32_t(mix64(seed + 1)));
  const uint32_t y = owen_of_reversed(kReversedSecond(k), uint32_t(mix64(seed + 2)));
  return {to_unit(x), to_unit(y)};
}

Sampler::Sampler(SamplingMode mode, uint64_t seed, uint64_t domain, uint64_t index, uint32_t sample)
    : mode_(mode),
      stream_(seed, domain, index, sample),
      base_(hash_combine(hash_combine(hash_combine(seed, domain ^ 0x5A17ull), index),
                         uint64_t(replicate(sample)))),
      index_(sample >> 1) {}

uint64_t Sampler::dimension_seed() { return hash_combine(base_, uint64_t(dimension_++)); }

double Sampler::next1d() {
  if (mode_ == SamplingMode::independent) return stream_.next();
  // A shuffled, scrambled van der Corput sequence.
  const uint64_t seed = dimension_seed();
  return to_unit(owen_of_reversed(shuffled_index(index_, seed), uint32_t(mix64(seed + 1))));
}

glm::dvec2 Sampler::next2d() {
  if (mode_ == SamplingMode::independent) {
    const double u = stream_.next();
    return {u, stream_.next()};
  }
  return scrambled_sobol_2d(index_, dimension_seed());
}

}  // namespace countershade
