#include "core/text.h"

#include <ft2build.h>
#include FT_FREETYPE_H

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <string>

#include "core/utf8.h"

namespace countershade {
namespace {

const char* const kFontFile = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

// One FreeType face for the process, used under its lock (a face is not thread-safe).
class Font {
 public:
  static Font& instance() {
    static Font font;
    return font;
  }
  std::mutex& mutex() { return mutex_; }
  // The face at `size_px` pixels per em.
  FT_Face face(int size_px) {
    if (FT_Set_Pixel_Sizes(face_, 0, FT_UInt(size_px)) != 0)
      throw std::runtime_error(std::string("text: cannot size ") + kFontFile + " to " +
                               std::to_string(size_px) + " px");
    return face_;
  }

 private:
  Font() {
    if (FT_Init_FreeType(&library_) != 0) throw std::runtime_error("text: FreeType did not start");
    if (FT_New_Face(library_, kFontFile, 0, &face_) != 0)
      throw std::runtime_error(std::string("text: cannot read the font ") + kFontFile +
                               " (Debian's fonts-dejavu-core; scripts/setup installs it)");
  }
  ~Font() {
    FT_Done_Face(face_);
    FT_Done_FreeType(library_);
  }
  FT_Library library_ = nullptr;
  FT_Face face_ = nullptr;
  std::mutex mutex_;
};

// Blends one rendered glyph's coverage into the image, its bitmap's top-left at (left, top).
void blend_glyph(Image& image, const FT_Bitmap& bitmap, int left, int top, const float colour[3]) {
  const int colours = std::min(image.channels, 3);
  for (int row = 0; row < int(bitmap.rows); ++row) {
    const int y = top + row;
    if (y < 0 || y >= image.height) continue;
    for (int col = 0; col < int(bitmap.width); ++col) {
      const int x = left + col;
      if (x < 0 || x >= image.width) continue;
      const float a = float(bitmap.buffer[row * bitmap.pitch + col]) / 255.0f;
      if (a == 0) continue;
      for (int c = 0; c < colours; ++c)
        image.at(x, y, c) += a * (colour[image.channels == 1 ? 0 : c] - image.at(x, y, c));
    }
  }
}

}  // namespace

int text_width(std::string_view utf8, int size_px) {
  Font& font = Font::instance();
  std::lock_guard<std::mutex> lock(font.mutex());
  FT_Face face = font.face(size_px);
  long advance = 0;  // 26.6 fixed point
  for (char32_t c : decode_utf8(utf8))
    if (FT_Load_Char(face, FT_ULong(c), FT_LOAD_DEFAULT) == 0) advance += face->glyph->advance.x;
  return int(std::ceil(double(advance) / 64.0));
}

void draw_text(Image& image, int x, int baseline, std::string_view utf8, int size_px,
               const float colour[3]) {
  Font& font = Font::instance();
  std::lock_guard<std::mutex> lock(font.mutex());
  FT_Face face = font.face(size_px);
  long pen = long(x) * 64;  // 26.6 fixed point
  for (char32_t c : decode_utf8(utf8)) {
    if (FT_Load_Char(face, FT_ULong(c), FT_LOAD_RENDER) != 0) continue;
    const FT_GlyphSlot g = face->glyph;
    blend_glyph(image, g->bitmap, int(pen >> 6) + g->bitmap_left, baseline - g->bitmap_top, colour);
    pen += g->advance.x;
  }
}

}  // namespace countershade
