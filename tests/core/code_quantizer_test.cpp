#include "core/code_quantizer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <functional>
#include <random>

#include "core/image.h"

namespace countershade {
namespace {

// A lookup against the reference at a million random values over the decades of [0, 1] and
// at and beside values stepping through every threshold.
void expect_lookup_exact(const std::function<uint32_t(double)>& lookup,
                         const std::function<uint32_t(double)>& reference) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> exponent(-32.0, 0.0);
  for (int i = 0; i < 1000000; ++i) {
    const double x = std::exp2(exponent(random));
    ASSERT_EQ(lookup(x), reference(x)) << x;
  }
  for (double x = 1e-9; x < 1.0; x = std::nextafter(x * 1.0005, 2.0)) {
    ASSERT_EQ(lookup(x), reference(x)) << x;
    ASSERT_EQ(lookup(std::nextafter(x, 0.0)), reference(std::nextafter(x, 0.0))) << x;
  }
}

// The code through the table's packed words, as the vector composition reads them (the formula
// of CodeQuantizer::Table::packed), for x in [0, 1].
uint32_t packed_code(const CodeQuantizer::Table& t, double x) {
  const int64_t bits = std::bit_cast<int64_t>(x);
  const int64_t raw = (bits >> t.shift) - t.offset;
  const uint64_t word = t.packed[std::clamp(raw, int64_t(0), t.last)];
  const uint64_t low = uint64_t(bits) & ((uint64_t(1) << t.shift) - 1);
  return uint32_t(word >> 48) + uint32_t(raw >= 0 && low >= (word & CodeQuantizer::kLowBits));
}

// The fast lookup gives quantize(float(encode(x)), bits) for every x: at and beside every
// threshold, and at a million random values spread over the decades of [0, 1]. So do the table's
// packed words.
void expect_exact(const DisplayEncoding& encoding, int bits, bool expect_table) {
  CodeQuantizer q(encoding, bits);
  EXPECT_EQ(q.uses_table(), expect_table);
  auto reference = [&](double x) { return quantize(float(encoding.encode(x)), bits); };
  auto code = [&](double x) { return q.code(x); };
  auto packed = [&](double x) { return expect_table ? packed_code(q.table(), x) : q.code(x); };
  for (auto lookup :
       {std::function<uint32_t(double)>(code), std::function<uint32_t(double)>(packed)})
    expect_lookup_exact(lookup, reference);
  for (double x : {-1.0, 0.0, 1.0, 2.0, std::nan("")}) EXPECT_EQ(q.code(x), reference(x)) << x;
  for (double x : {0.0, -0.0, 1.0, 1e-300}) EXPECT_EQ(packed(x), reference(x)) << x;
  const uint32_t max_code = (1u << bits) - 1u;
  EXPECT_EQ(q.code(1.0), max_code);
  EXPECT_EQ(q.value(1.0), 1.0f);
}

TEST(CodeQuantizer, MatchesTheReferenceQuantisationForEveryEncoding) {
  expect_exact(DisplayEncoding::srgb(), 8, true);
  expect_exact(DisplayEncoding::gamma(2.2), 8, true);
  expect_exact(DisplayEncoding::lut({0, 0.25, 0.5, 1}, {0, 0.04, 0.25, 1}), 8, true);
  expect_exact(DisplayEncoding::srgb(), 16, false);  // 16 bits: a binary search, no table
}

// The product in double gives the division's float for every code of every depth up to 16 bits.
TEST(CodeQuantizer, CodeFractionEqualsTheDivisionForEveryCode) {
  for (int bits = 1; bits <= 16; ++bits) {
    const uint32_t max_code = (1u << bits) - 1u;
    const float levels = float(max_code);
    const double inverse = 1.0 / double(levels);
    for (uint32_t k = 0; k <= max_code; ++k)
      ASSERT_EQ(code_fraction(k, inverse), float(k) / levels) << bits << " " << k;
  }
}

TEST(CodeQuantizer, IsSharedPerEncodingAndBitDepth) {
  const CodeQuantizer& a = CodeQuantizer::shared(DisplayEncoding::srgb(), 8);
  EXPECT_EQ(&a, &CodeQuantizer::shared(DisplayEncoding::srgb(), 8));
  EXPECT_NE(&a, &CodeQuantizer::shared(DisplayEncoding::gamma(2.2), 8));
}

}  // namespace
}  // namespace countershade
