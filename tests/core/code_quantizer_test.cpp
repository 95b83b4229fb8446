#include "core/code_quantizer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/image.h"

namespace countershade {
namespace {

// The fast lookup gives quantize(float(encode(x)), bits) for every x: at and beside every
// threshold, and at a million random values spread over the decades of [0, 1].
void expect_exact(const DisplayEncoding& encoding, int bits, bool expect_table) {
  CodeQuantizer q(encoding, bits);
  EXPECT_EQ(q.uses_table(), expect_table);
  auto reference = [&](double x) { return quantize(float(encoding.encode(x)), bits); };
  std::mt19937_64 random(bits);
  std::uniform_real_distribution<double> exponent(-32.0, 0.0);
  for (int i = 0; i < 1000000; ++i) {
    const double x = std::exp2(exponent(random));
    ASSERT_EQ(q.code(x), reference(x)) << x;
  }
  // Every threshold: the code changes exactly there.
  const uint32_t max_code = (1u << bits) - 1u;
  for (double x = 1e-9; x < 1.0; x = std::nextafter(x * 1.0005, 2.0)) {
    ASSERT_EQ(q.code(x), reference(x)) << x;
    ASSERT_EQ(q.code(std::nextafter(x, 0.0)), reference(std::nextafter(x, 0.0))) << x;
  }
  for (double x : {-1.0, 0.0, 1.0, 2.0, std::nan("")}) EXPECT_EQ(q.code(x), reference(x)) << x;
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
    for (uint32_t k = 0; k <= max_code; ++k) ASSERT_EQ(code_fraction(k, inverse), float(k) / levels) << bits << " " << k;
  }
}

TEST(CodeQuantizer, IsSharedPerEncodingAndBitDepth) {
  const CodeQuantizer& a = CodeQuantizer::shared(DisplayEncoding::srgb(), 8);
  EXPECT_EQ(&a, &CodeQuantizer::shared(DisplayEncoding::srgb(), 8));
  EXPECT_NE(&a, &CodeQuantizer::shared(DisplayEncoding::gamma(2.2), 8));
}

}  // namespace
}  // namespace countershade
