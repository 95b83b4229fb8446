// The audit's CIEDE2000 cache gives exactly what ciede2000 gives, whatever the slots hold.
#include "audit/delta_e_cache.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace countershade {
namespace {

// Pairs drawn from a few colours, so that most repeat, in random order.
std::vector<std::pair<Lab, Lab>> repeating_pairs(size_t count) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> lightness(0, 100), chroma(-60, 60);
  std::vector<Lab> colours;
  for (int k = 0; k < 12; ++k)
    colours.push_back({lightness(random), chroma(random), chroma(random)});
  colours.push_back({50, 0, 0});  // neutral, where the hue is undefined
  colours.push_back({50, 0, -0.0});
  std::uniform_int_distribution<size_t> pick(0, colours.size() - 1);
  std::vector<std::pair<Lab, Lab>> pairs;
  for (size_t i = 0; i < count; ++i)
    pairs.emplace_back(colours[pick(random)], colours[pick(random)]);
  return pairs;
}

TEST(DeltaECache, EveryCallGivesCiede2000sNumberWhenEveryPairSharesOneSlot) {
  DeltaECache cache;
  for (const auto& [reference, stimulus] : repeating_pairs(2000)) {
    const double expected = ciede2000(reference, stimulus);
    EXPECT_EQ(cache(reference, stimulus, 0), expected);
  }
}

TEST(DeltaECache, RepeatedPairsHitAndStillGiveCiede2000sNumber) {
  DeltaECache cache;
  int pair_number = 0;
  for (const auto& [reference, stimulus] : repeating_pairs(2000)) {
    // The hash of the first member alone: pairs that share it evict each other.
    const uint64_t hash = uint64_t(reference.L * 1000) + uint64_t(++pair_number % 3);
    EXPECT_EQ(cache(reference, stimulus, hash), ciede2000(reference, stimulus));
    EXPECT_EQ(cache(stimulus, reference, hash), ciede2000(stimulus, reference));
  }
}

}  // namespace
}  // namespace countershade
