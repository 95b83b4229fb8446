#include "core/one_line.h"

#include <gtest/gtest.h>

namespace countershade {
namespace {

TEST(OneLine, KeepsPrintableTextAndWellFormedUtf8) {
  EXPECT_EQ(one_line("scene.json: camera: fov: must be in (0, 180), got 200"),
            "scene.json: camera: fov: must be in (0, 180), got 200");
  EXPECT_EQ(one_line("σ = 0.5, λ ≥ 0, 🙂"),
            "σ = 0.5, λ ≥ 0, 🙂");  // two, three and four bytes
}

TEST(OneLine, EscapesControlCharactersAndBytesThatAreNotUtf8) {
  EXPECT_EQ(one_line("a\nb\r\tc"), "a\\x0ab\\x0d\\x09c");
  EXPECT_EQ(one_line(std::string("last read: '\x89PNG'")), "last read: '\\x89PNG'");
  EXPECT_EQ(one_line(std::string("\0", 1)), "\\x00");
  EXPECT_EQ(one_line("\x7f"), "\\x7f");
  // Broken sequences: a lead byte without its continuation, cut off at the end, overlong,
  // a surrogate, past U+10FFFF.
  EXPECT_EQ(one_line("\xcf"
                     "a"),
            "\\xcfa");
  EXPECT_EQ(one_line("\xe2\x89"), "\\xe2\\x89");
  EXPECT_EQ(one_line("\xc0\xaf"), "\\xc0\\xaf");
  EXPECT_EQ(one_line("\xed\xa0\x80"), "\\xed\\xa0\\x80");
  EXPECT_EQ(one_line("\xf4\x90\x80\x80"), "\\xf4\\x90\\x80\\x80");
}

}  // namespace
}  // namespace countershade
