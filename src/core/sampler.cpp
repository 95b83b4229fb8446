#include "core/sampler.h"

#include <algorithm>

#include "core/isa.h"

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

double to_unit(uint32_t x) { return double(x) * 0x1p-32; }

// The shuffled index: an Owen scramble of the sample number, which keeps every aligned block of
// 2^m numbers in one aligned block.
uint32_t shuffled_of_reversed(uint32_t reversed_index, uint64_t seed) {
  return owen_of_reversed(reversed_index, uint32_t(mix64(seed)));
}
uint32_t shuffled_index(uint32_t index, uint64_t seed) {
  return shuffled_of_reversed(reverse_bits(index), seed);
}

// The point's two coordinates from the index already reversed (the same for every dimension).
inline void sobol_2d_of_reversed(uint32_t reversed_index, uint64_t seed, double& u1, double& u2) {
  const uint32_t k = shuffled_of_reversed(reversed_index, seed);
  // Dimension 0 is the van der Corput sequence reverse(k): its reversal is k itself.
  u1 = to_unit(owen_of_reversed(k, uint32_t(mix64(seed + 1))));
  u2 = to_unit(owen_of_reversed(reversed_second_sobol_dimension(k), uint32_t(mix64(seed + 2))));
}

// Consecutive points of one sequence side by side: the same integer operations as one point at
// a time, which the compiler turns into vector lanes (64-bit multiplies and byte swaps).
COUNTERSHADE_CLONES
void sobol_2d_lanes(uint64_t seed, uint32_t first_index, double* __restrict u1,
                    double* __restrict u2) {
  for (uint32_t i = 0; i < uint32_t(Sampler::kBlockLanes); ++i)
    sobol_2d_of_reversed(reverse_bits(first_index + i), seed, u1[i], u2[i]);
}

}  // namespace

uint32_t reversed_second_sobol_dimension(uint32_t k) {
  // The generator of the second dimension (polynomial x + 1) reversed is the Pascal matrix mod 2:
  // index bit i adds (1 + x)^i, whose bit j is set where j's bits are a subset of i's (Lucas).
  // So bit j of the result is the parity of the index bits at the supersets of j: a superset sum
  // over the five bits of the bit position, one shift per bit.
  uint32_t y = k;
  y ^= (y >> 1) & 0x55555555u;
  y ^= (y >> 2) & 0x33333333u;
  y ^= (y >> 4) & 0x0F0F0F0Fu;
  y ^= (y >> 8) & 0x00FF00FFu;
  y ^= (y >> 16) & 0x0000FFFFu;
  return y;
}

glm::dvec2 scrambled_sobol_2d(uint32_t index, uint64_t seed) {
  glm::dvec2 u;
  sobol_2d_of_reversed(reverse_bits(index), seed, u.x, u.y);
  return u;
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

Sampler::Block::Block(Sampler& sampler, int count) : sampler_(sampler) {
  if (sampler.mode_ == SamplingMode::independent) return;
  seed_ = sampler.dimension_seed();
  first_index_ = uint32_t(count) * sampler.index_;
}

void Sampler::Block::points(int first, int n, double* u1, double* u2) const {
  if (sampler_.mode_ == SamplingMode::independent) {
    for (int i = 0; i < n; ++i) u1[i] = sampler_.stream_.next(), u2[i] = sampler_.stream_.next();
    return;
  }
  if (n == 1)
    return sobol_2d_of_reversed(reverse_bits(first_index_ + uint32_t(first)), seed_, *u1, *u2);
  double a[kBlockLanes], b[kBlockLanes];
  sobol_2d_lanes(seed_, first_index_ + uint32_t(first), a, b);
  std::copy_n(a, n, u1);
  std::copy_n(b, n, u2);
}

}  // namespace countershade
