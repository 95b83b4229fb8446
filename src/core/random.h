#pragma once
// Counter-based random numbers: every value is a pure function of (seed, stream, index, dimension),
// so results do not depend on thread count or scheduling.

#include <cstdint>
#include <string_view>

namespace countershade {

// SplitMix64 finaliser: a bijective 64-bit mix with good avalanche.
inline uint64_t mix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

inline uint64_t hash_combine(uint64_t a, uint64_t b) { return mix64(a ^ mix64(b)); }

// FNV-1a of a string: a stable key for names (subject ids, conditions) in seeds.
inline uint64_t hash_string(std::string_view text) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : text) h = (h ^ c) * 1099511628211ull;
  return h;
}

// A deterministic stream of uniform numbers in [0,1) for one shading sample.
class SampleStream {
 public:
  SampleStream(uint64_t seed, uint64_t domain, uint64_t index, uint64_t sample)
      : key_(hash_combine(hash_combine(hash_combine(seed, domain), index), sample)) {}

  double next() { return double(mix64(key_ + 0x632BE59BD9B4E019ull * ++counter_) >> 11) * 0x1p-53; }

 private:
  uint64_t key_;
  uint64_t counter_ = 0;
};

// Domains keep pixel and vertex streams apart.
enum : uint64_t { kDomainPixel = 1, kDomainVertex = 2, kDomainCamera = 3, kDomainTriangle = 4 };

}  // namespace countershade
