#include "core/display.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"

namespace countershade {
namespace {

TEST(Display, EncodingsInvertEachOther) {
  DisplayEncoding encodings[] = {DisplayEncoding::srgb(), DisplayEncoding::gamma(2.4),
                                 DisplayEncoding::lut({0, 0.5, 1}, {0, 0.2, 1})};
  for (const auto& e : encodings)
    for (double x = 0; x <= 1.0; x += 0.01)
      EXPECT_NEAR(e.decode(e.encode(x)), x, 1e-9) << e.describe();
}

TEST(Display, KnownValues) {
  EXPECT_NEAR(DisplayEncoding::srgb().encode(0.5), 0.7353569830524495, 1e-12);
  EXPECT_NEAR(DisplayEncoding::gamma(2.0).encode(0.25), 0.5, 1e-12);
  // Table measured in arbitrary units is normalised: code 128/255 gave 20% of the peak.
  DisplayEncoding lut = DisplayEncoding::lut({0, 128, 255}, {0.5, 20.4, 100.0});
  EXPECT_NEAR(lut.decode(128.0 / 255.0), (20.4 - 0.5) / 99.5, 1e-12);
  EXPECT_DOUBLE_EQ(DisplayEncoding::srgb().encode(2.0), 1.0);  // clipped
  EXPECT_DOUBLE_EQ(DisplayEncoding::srgb().encode(std::nan("")), 0.0);
}

TEST(Display, RejectsBadTables) {
  EXPECT_THROW(DisplayEncoding::lut({0, 1}, {1, 0}), InputError);
  EXPECT_THROW(DisplayEncoding::lut({0}, {0}), InputError);
  EXPECT_THROW(DisplayEncoding::gamma(-1), InputError);
}

}  // namespace
}  // namespace countershade
