// Text in images: UTF-8 decoded to code points and drawn with the font's own glyphs, so a caption
// keeps σ, λ, ±, ° (a decoder that keeps only a sequence's last byte draws λ as ';' and ± as '1').

#include <ft2build.h>
#include <gtest/gtest.h>
#include FT_FREETYPE_H

#include <filesystem>

#include "core/image.h"
#include "core/text.h"
#include "core/utf8.h"
#include "test_util.h"

namespace countershade {
namespace {

const float kWhite[3] = {1.0f, 1.0f, 1.0f};

Image drawn(const std::string& text, int size_px = 24) {
  Image image(64, 40, 3, 0.0f);
  draw_text(image, 8, 30, text, size_px, kWhite);
  return image;
}

double difference(const Image& a, const Image& b) {
  double sum = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    sum += std::abs(double(a.pixels[i]) - double(b.pixels[i]));
  return sum;
}

TEST(Text, Utf8IsDecodedToCodePoints) {
  EXPECT_EQ(decode_utf8("σ = 0.12, λ = 3, L* ±2, 1°"),
            std::u32string(U"σ = 0.12, λ = 3, L* ±2, 1°"));
  EXPECT_EQ(decode_utf8("a\xE2\x89\xA4"
                        "b"),
            std::u32string(U"a≤b"));
  EXPECT_EQ(decode_utf8("\xF0\x9F\x98\x80"), std::u32string(U"\U0001F600"));
  // Bytes that start no well-formed sequence: one replacement character each.
  EXPECT_EQ(decode_utf8("x\xC3"
                        "y\xBB"),
            std::u32string(U"x\uFFFDy\uFFFD"));
  EXPECT_EQ(decode_utf8("\xC0\xAF"), std::u32string(U"\uFFFD\uFFFD"));  // an overlong '/'
}

// Each character of a caption of this field is drawn with its own glyph: λ differs from ';', ±
// from '1', ° from '0', σ from a missing-glyph box (code point 3).
TEST(Text, GreekAndSymbolsAreNotTheirLastBytes) {
  const std::pair<const char*, const char*> pairs[] = {
      {"λ", ";"}, {"±", "1"}, {"°", "0"}, {"σ", "\x03"}};
  for (const auto& [character, mangled] : pairs) {
    const Image a = drawn(character), b = drawn(mangled);
    EXPECT_GT(difference(a, b), 20.0) << character;
    EXPECT_GT(difference(a, Image(64, 40, 3, 0.0f)), 20.0) << character << " drew nothing";
  }
}

// The pixels drawn for λ are FreeType's own rendering of U+03BB from the same font, placed at
// the pen position and baseline.
TEST(Text, ACharacterMatchesItsGlyphsOwnRendering) {
  FT_Library library;
  ASSERT_EQ(FT_Init_FreeType(&library), 0);
  FT_Face face;
  ASSERT_EQ(FT_New_Face(library, "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf", 0, &face), 0);
  ASSERT_EQ(FT_Set_Pixel_Sizes(face, 0, 24), 0);
  ASSERT_EQ(FT_Load_Char(face, 0x03BB, FT_LOAD_RENDER), 0);
  ASSERT_NE(FT_Get_Char_Index(face, 0x03BB), 0u) << "the font has λ";
  const FT_Bitmap& bitmap = face->glyph->bitmap;
  const int left = 8 + face->glyph->bitmap_left, top = 30 - face->glyph->bitmap_top;
  Image expected(64, 40, 3, 0.0f);
  for (int row = 0; row < int(bitmap.rows); ++row)
    for (int col = 0; col < int(bitmap.width); ++col)
      for (int c = 0; c < 3; ++c)
        expected.at(left + col, top + row, c) =
            float(bitmap.buffer[row * bitmap.pitch + col]) / 255.0f;
  FT_Done_Face(face);
  FT_Done_FreeType(library);
  const Image got = drawn("λ");
  EXPECT_LT(difference(got, expected), 1e-4);
  EXPECT_GT(difference(expected, Image(64, 40, 3, 0.0f)), 20.0);
}

TEST(Text, WidthFollowsTheGlyphsAdvances) {
  EXPECT_EQ(text_width("", 14), 0);
  EXPECT_GT(text_width("λλλλ", 14), text_width("λλ", 14));
  EXPECT_NEAR(text_width("λλλλ", 14), 2 * text_width("λλ", 14), 1);
}

// `sheet` captions in this field's characters: a caption of λ is not a caption of ';'.
TEST(Text, SheetCaptionsKeepTheirCharacters) {
  testing::TempDir dir;
  write_image(dir / "a.png",
              Image(400, 30, 3, 0.2f));  // its thumbnail is wider than either caption
  auto sheet = [&](const std::string& caption, const std::string& name) {
    const auto r = testing::run_cli("sheet '" + (dir / "a.png").string() + "=" + caption + "' -o " +
                                    (dir / name).string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return read_image(dir / name);
  };
  const Image greek = sheet("σ = 0.12, λ = 3, L* ±2, 1°", "greek.png");
  const Image mangled = sheet("\x03 = 0.12, ; = 3, L* 12, 10", "mangled.png");
  ASSERT_EQ(greek.width, mangled.width);
  ASSERT_EQ(greek.height, mangled.height);
  EXPECT_GT(difference(greek, mangled), 50.0);
}

}  // namespace
}  // namespace countershade
