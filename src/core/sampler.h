#pragma once
// The random numbers of one shading sample.
//
// `sobol` (the default): every pair of dimensions (the pixel position, each light sample, each
// environment or occlusion direction) takes its point from its own 2D Sobol (0,2)-sequence,
// Owen-scrambled and index-shuffled with hash-based permutations (the formulas of Burley 2020, as
// in pbrt-v4's padded Sobol sampler). The samples of a pixel are split into two replicates with
// independent scrambles, so the spread of the two replicate means estimates the pixel's error.
// Shuffling the index within aligned blocks keeps every prefix of 2^k samples of a replicate a
// (0,k,2)-net, so the sampling stays well stratified at any count the adaptive sampler stops at.
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
  // The next `count` 2D points, as that many next2d() calls give them, drawn side by side.
  void next2d_many(int count, double* u1, double* u2);

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

// The Owen-scrambled, index-shuffled 2D Sobol point `index` for a seed: exposed for tests.
glm::dvec2 scrambled_sobol_2d(uint32_t index, uint64_t seed);

// The second Sobol dimension's value for index k, bit-reversed: exposed for tests.
uint32_t reversed_second_sobol_dimension(uint32_t k);

}  // namespace countershade
