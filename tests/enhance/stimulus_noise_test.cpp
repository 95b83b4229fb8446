#include "enhance/stimulus_noise.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace countershade {
namespace {

// The closed forms at both ends: no noise, no difference; a small error flips a rounding by one
// step with probability 2r/√π, a variance of r/√π per image; a large one adds the rounding's own
// 1/12 variance.
TEST(StimulusNoise, QuantisedNoiseHasItsLimits) {
  EXPECT_EQ(quantized_noise_steps(0.0), 0.0);
  EXPECT_NEAR(quantized_noise_steps(0.001), std::sqrt(0.001 / std::sqrt(M_PI)), 2e-4);
  EXPECT_NEAR(quantized_noise_steps(10.0), std::sqrt(100.0 + 1.0 / 12.0), 1e-6);
  EXPECT_NEAR(quantized_noise_steps(-10.0), quantized_noise_steps(10.0), 1e-12);
  EXPECT_EQ(quantized_noise_steps(INFINITY), INFINITY);
  EXPECT_TRUE(std::isnan(quantized_noise_steps(NAN)));  // not a table index
}

// Against simulation: two renders of a pixel differ by independent normal errors before rounding.
TEST(StimulusNoise, QuantisedNoiseMatchesASimulation) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> position(0.0, 1.0);
  for (double r : {0.1, 0.3, 0.7, 1.5, 3.0}) {
    std::normal_distribution<double> error(0.0, r);
    double sum = 0;
    const int n = 400000;
    for (int i = 0; i < n; ++i) {
      const double x = position(rng);
      const double d = std::round(x + error(rng)) - std::round(x + error(rng));
      sum += d * d / 2.0;
    }
    EXPECT_NEAR(quantized_noise_steps(r), std::sqrt(sum / n),
                0.01 * quantized_noise_steps(r) + 2e-3)
        << r;
  }
}

// The p99 of |e| over pixels when each pixel's error is normal with its own σ.
TEST(StimulusNoise, SummaryGivesRmsAndTheNinetyNinthPercentile) {
  const NoiseSummary same = summarize_noise(std::vector<float>(1000, 0.4f));
  EXPECT_NEAR(same.rms, 0.4, 1e-6);
  EXPECT_NEAR(same.p99, 2.5758 * 0.4, 2e-3);  // two-sided 99 % point of the normal
  std::vector<float> half(1000, 0.0f);
  for (size_t i = 0; i < 500; ++i) half[i] = 1.0f;
  const NoiseSummary mixed = summarize_noise(half);
  EXPECT_NEAR(mixed.rms, std::sqrt(0.5), 1e-6);
  EXPECT_NEAR(mixed.p99, 2.3263, 3e-3);  // 2 % of the noisy half exceed it
  EXPECT_EQ(summarize_noise(std::vector<float>(10, 0.0f)).p99, 0.0);
  std::vector<float> unbounded(10, 0.5f);
  unbounded[3] = INFINITY;  // a pixel at an absurd λ
  EXPECT_EQ(summarize_noise(unbounded).rms, INFINITY);
  EXPECT_EQ(summarize_noise(unbounded).p99, INFINITY);
}

// Over a wide spread of σ, the p99 is where the share of pixels' errors beyond it is 1 %, found
// here by bisection on every pixel's own σ (the summary works on a histogram of 2048 bins).
TEST(StimulusNoise, TheNinetyNinthPercentileOfASpreadOfSigmasIsWhereOnePercentExceedIt) {
  std::vector<float> sigma(20000);
  for (size_t i = 0; i < sigma.size(); ++i)  // 0.01 to 3 L*, most pixels quiet, a few noisy
    sigma[i] = float(0.01 * std::pow(300.0, std::pow(double(i) / double(sigma.size()), 3.0)));
  auto exceed = [&](double x) {
    double share = 0;
    for (float s : sigma) share += std::erfc(x / (double(s) * std::sqrt(2.0)));
    return share / double(sigma.size());
  };
  double lo = 0, hi = 20;
  for (int i = 0; i < 80; ++i) (exceed(0.5 * (lo + hi)) > 0.01 ? lo : hi) = 0.5 * (lo + hi);
  const double p99 = summarize_noise(sigma).p99;
  EXPECT_NEAR(p99, lo, 2e-3 * lo);
  EXPECT_NEAR(exceed(p99), 0.01, 1e-4);
  // Fewer than 1 % of the pixels noisy at all: |e| exceeds 0 no more often than that.
  std::vector<float> quiet(1000, 0.0f);
  quiet[7] = 2.0f;
  EXPECT_EQ(summarize_noise(quiet).p99, 0.0);
}

}  // namespace
}  // namespace countershade
