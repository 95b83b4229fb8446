#include "core/sampler.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/random.h"

namespace countershade {
namespace {

// Every elementary interval [i/2^a, (i+1)/2^a) × [j/2^b, (j+1)/2^b) with a + b = m holds exactly
// one of the 2^m points: a (0,m,2)-net in base 2.
bool is_net(const std::vector<glm::dvec2>& points, int m) {
  for (int a = 0; a <= m; ++a) {
    const int b = m - a;
    std::vector<int> count(size_t(1) << m, 0);
    for (const auto& p : points) {
      const int i = int(p.x * double(1 << a)), j = int(p.y * double(1 << b));
      if (++count[size_t(i) * (size_t(1) << b) + size_t(j)] > 1) return false;
    }
  }
  return true;
}

uint32_t reversed(uint32_t x) {
  uint32_t r = 0;
  for (int bit = 0; bit < 32; ++bit) r |= ((x >> bit) & 1u) << (31 - bit);
  return r;
}

TEST(Sampler, TheSecondDimensionFollowsItsGenerator) {
  // The generator matrix of the polynomial x + 1: direction numbers v_0 = 2^31 and
  // v_i = v_(i−1) xor (v_(i−1) >> 1); index k's value is the xor of v_i over k's set bits.
  uint32_t v[32];
  v[0] = 1u << 31;
  for (int i = 1; i < 32; ++i) v[i] = v[i - 1] ^ (v[i - 1] >> 1);
  auto by_generator = [&](uint32_t k) {
    uint32_t x = 0;
    for (int i = 0; i < 32; ++i)
      if ((k >> i) & 1u) x ^= v[i];
    return reversed(x);
  };
  for (uint32_t k = 0; k < 70000; ++k)
    ASSERT_EQ(reversed_second_sobol_dimension(k), by_generator(k)) << k;
  for (uint64_t i = 0; i < 100000; ++i) {
    const uint32_t k = uint32_t(mix64(i));
    ASSERT_EQ(reversed_second_sobol_dimension(k), by_generator(k)) << k;
  }
}

// A block's points, drawn side by side and one at a time (the scalar path), are the same bits.
TEST(Sampler, BlockPointsDrawnSideBySideAreThePointsDrawnOneAtATime) {
  for (int count : {2, 3, 8, 9, 20})
    for (uint32_t sample : {0u, 1u, 6u, 1001u}) {
      Sampler sampler(SamplingMode::sobol, 7, kDomainPixel, 12345, sample);
      const Sampler::Block block = sampler.next2d_block(count);
      for (int first = 0; first < count; first += Sampler::kBlockLanes) {
        const int n = std::min(Sampler::kBlockLanes, count - first);
        double u1[Sampler::kBlockLanes], u2[Sampler::kBlockLanes];
        block.points(first, n, u1, u2);
        for (int i = 0; i < n; ++i) {
          double v1 = -1, v2 = -1;
          block.points(first + i, 1, &v1, &v2);
          ASSERT_EQ(u1[i], v1) << count << " " << sample << " " << first + i;
          ASSERT_EQ(u2[i], v2) << count << " " << sample << " " << first + i;
        }
      }
    }
}

// A block of one point is the next dimension's point, so a light with one sample draws what it
// drew before blocks; in independent mode a block is the next numbers of the stream.
TEST(Sampler, ABlockTakesOneDimensionAndOfOnePointIsTheNextPoint) {
  for (SamplingMode mode : {SamplingMode::sobol, SamplingMode::independent})
    for (uint32_t sample : {0u, 1u, 6u, 1001u}) {
      Sampler one(mode, 7, kDomainPixel, 12345, sample),
          block(mode, 7, kDomainPixel, 12345, sample);
      EXPECT_EQ(one.next1d(), block.next1d());
      double u1 = -1, u2 = -1;
      block.next2d_block(1).points(0, 1, &u1, &u2);
      EXPECT_EQ(one.next2d(), glm::dvec2(u1, u2));
      if (mode == SamplingMode::independent) {
        double v1[3], v2[3];
        block.next2d_block(3).points(0, 3, v1, v2);
        for (int i = 0; i < 3; ++i) EXPECT_EQ(one.next2d(), glm::dvec2(v1[i], v2[i])) << i;
      } else {
        block.next2d_block(3);
        one.next2d();
      }
      EXPECT_EQ(one.next2d(), block.next2d()) << "a block moves on by one dimension";
    }
}

// The lever of blocks: a light's count points at each of a replicate's first 2^k samples are
// the first count·2^k points of one scrambled sequence, a (0,m,2)-net together, where separate
// dimensions would give count nets of 2^k points that know nothing of each other.
TEST(Sampler, ALightsPointsOverAReplicatesSamplesFormOneNet) {
  for (int count : {2, 4, 8})
    for (uint64_t pixel : {12345ull, 99ull}) {
      std::vector<glm::dvec2> points;
      for (uint32_t s = 0; s < 256; s += 2) {  // replicate 0
        Sampler sampler(SamplingMode::sobol, 7, kDomainPixel, pixel, s);
        sampler.next2d();  // the pixel position's dimension
        const Sampler::Block block = sampler.next2d_block(count);
        for (int i = 0; i < count; ++i) {
          double u1, u2;
          block.points(i, 1, &u1, &u2);
          points.emplace_back(u1, u2);
        }
        const size_t n = points.size();
        if ((n & (n - 1)) == 0) {
          EXPECT_TRUE(is_net(points, int(std::log2(double(n)))))
              << count << " points a sample, " << n << " points";
        }
      }
    }
}

TEST(Sampler, EveryPowerOfTwoPrefixOfTheScrambledSequenceIsANet) {
  for (uint64_t seed : {1ull, 42ull, 0xDEADBEEFull}) {
    std::vector<glm::dvec2> points;
    for (uint32_t i = 0; i < 1024; ++i) {
      const glm::dvec2 p = scrambled_sobol_2d(i, seed);
      ASSERT_GE(p.x, 0.0);
      ASSERT_LT(p.x, 1.0);
      ASSERT_GE(p.y, 0.0);
      ASSERT_LT(p.y, 1.0);
      points.push_back(p);
      const uint32_t n = i + 1;
      if ((n & (n - 1)) == 0) {
        EXPECT_TRUE(is_net(points, int(std::log2(double(n)))))
            << "seed " << seed << ", " << n << " points";
      }
    }
  }
}

TEST(Sampler, EachReplicateIsANetOfItsOwn) {
  // A pixel's samples alternate between two replicates; each replicate's first 2^m samples (of
  // any 2D dimension) form a net, and the two replicates are scrambled differently.
  for (int dimension = 0; dimension < 3; ++dimension) {
    std::vector<glm::dvec2> replicate[2];
    for (uint32_t s = 0; s < 512; ++s) {
      Sampler sampler(SamplingMode::sobol, 7, 1, 12345, s);
      glm::dvec2 p;
      for (int d = 0; d <= dimension; ++d) p = sampler.next2d();
      replicate[Sampler::replicate(s)].push_back(p);
    }
    EXPECT_TRUE(is_net(replicate[0], 8)) << dimension;
    EXPECT_TRUE(is_net(replicate[1], 8)) << dimension;
    EXPECT_NE(replicate[0][0], replicate[1][0]);
  }
}

TEST(Sampler, ValuesArePureFunctionsOfTheirArguments) {
  Sampler a(SamplingMode::sobol, 3, 2, 99, 17), b(SamplingMode::sobol, 3, 2, 99, 17);
  for (int i = 0; i < 8; ++i) EXPECT_EQ(a.next2d(), b.next2d());
  EXPECT_EQ(a.next1d(), b.next1d());
  Sampler other_pixel(SamplingMode::sobol, 3, 2, 100, 17),
      other_seed(SamplingMode::sobol, 4, 2, 99, 17);
  Sampler c(SamplingMode::sobol, 3, 2, 99, 17);
  const glm::dvec2 first = c.next2d();
  EXPECT_NE(first, other_pixel.next2d());
  EXPECT_NE(first, other_seed.next2d());
  // The independent mode is the counter-based stream.
  Sampler independent(SamplingMode::independent, 3, 2, 99, 17);
  SampleStream stream(3, 2, 99, 17);
  EXPECT_EQ(independent.next1d(), stream.next());
  const glm::dvec2 p = independent.next2d();
  EXPECT_EQ(p.x, stream.next());
  EXPECT_EQ(p.y, stream.next());
}

// The point of the scrambled sequence: integrating a smooth function over the unit square, the
// error falls much faster than with independent numbers. f(x, y) = x·y·e^(x+y) integrates to
// exactly 1 (∫x·e^x dx over [0,1] is 1).
TEST(Sampler, IntegratesSmoothFunctionsFarBetterThanIndependentNumbers) {
  auto f = [](glm::dvec2 p) { return p.x * p.y * std::exp(p.x + p.y); };
  double sobol_error = 0, independent_error = 0;
  constexpr int kTrials = 32, kSamples = 256;
  for (int t = 0; t < kTrials; ++t) {
    double s = 0, r = 0;
    SampleStream stream(uint64_t(t), 0, 0, 0);
    for (uint32_t i = 0; i < kSamples; ++i) {
      s += f(scrambled_sobol_2d(i, uint64_t(t) + 100));
      const double u = stream.next();
      r += f({u, stream.next()});
    }
    sobol_error += (s / kSamples - 1.0) * (s / kSamples - 1.0) / kTrials;
    independent_error += (r / kSamples - 1.0) * (r / kSamples - 1.0) / kTrials;
  }
  // Owen-scrambled nets converge at about N^-1.5 in RMS error for smooth integrands: at 256
  // samples that is more than 10 times lower than independent sampling's N^-0.5.
  EXPECT_LT(std::sqrt(sobol_error) * 10, std::sqrt(independent_error));
}

}  // namespace
}  // namespace countershade
