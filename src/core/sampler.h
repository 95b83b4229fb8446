#pragma once
// The random numbers of one shading sample.
//
// `sobol` (the default): every pair of dimensions (the pixel position, each light's samples, the
// environment's or occlusion's directions) takes its points from its own 2D Sobol
// (0,2)-sequence, Owen-scrambled and index-shuffled with hash-based permutations (the formulas of
// Burley 2020, as in pbrt-v4's padded Sobol sampler). A light with several samples at a shading
// point takes them as one block of consecutive points of its sequence (`next2d_block`). The samples
// of a pixel are split into two replicates with independent scrambles, so the spread of the two
// replicate means estimates the pixel's error. Shuffling the index within aligned blocks keeps
// every prefix of 2^k samples of a replicate a (0,k,2)-net, so the sampling stays well stratified
// at any count the adaptive sampler stops at.
//
// `independent`: every number from a counter-based hash (the renderer's earlier sampling), for
// comparisons.
//
// Every value is a pure function of (seed, domain, index, sample, dimension): images do not
// depend on threads or scheduling.

#include <cstdint>
#include <glm/vec2.hpp>

#include "core/random.h"

namespace countershade {

enum class SamplingMode { sobol, independent };

class Sampler {
 public:
  // `index`: the pixel, vertex or ring point; `sample`: its sample number (0, 1, 2, …).
  Sampler(SamplingMode mode, uint64_t seed, uint64_t domain, uint64_t index, uint32_t sample);

  double next1d();
  glm::dvec2 next2d();

  // The points of one light's `count` samples at this shading sample. In sobol mode they come
  // from one dimension pair's sequence, at indices count·i … count·i + count − 1 for this sample's
  // number i in its replicate: a pixel's first n samples then spread the light's count·n points
  // as one stratified sequence (a union of (0,m,2)-nets), not as count sequences of n points
  // each. In independent mode they are the next count pairs of numbers.
  class Block {
   public:
    // Points `first` … `first + n − 1` of the block (n ≤ kBlockLanes), drawn side by side.
    void points(int first, int n, double* u1, double* u2) const;
    // Point `i` of the block alone.
    glm::dvec2 point(int i) const {
      glm::dvec2 u;
      points(i, 1, &u.x, &u.y);
      return u;
    }

   private:
    friend class Sampler;
    Block(Sampler& sampler, int count);
    Sampler& sampler_;
    uint64_t seed_ = 0;
    uint32_t first_index_ = 0;
  };
  static constexpr int kBlockLanes = 8;
  Block next2d_block(int count) { return Block(*this, count); }

  // The replicate a sample belongs to (0 or 1).
  static int replicate(uint32_t sample) { return int(sample & 1u); }

 private:
  uint64_t dimension_seed();

  SamplingMode mode_;
  SampleStream stream_;  // independent mode
  uint64_t base_;        // sobol mode: the hash of (seed, domain, index, replicate)
  uint32_t index_;       // sobol mode: the sample's number within its replicate
  uint32_t dimension_ = 0;
};

// The Owen-scrambled, index-shuffled 2D Sobol point `index` for a seed (a block's points are
// those of the sample's own seed): exposed for tests.
glm::dvec2 scrambled_sobol_2d(uint32_t index, uint64_t seed);

// The second Sobol dimension's value for index k, bit-reversed: exposed for tests.
uint32_t reversed_second_sobol_dimension(uint32_t k);

}  // namespace countershade
