#pragma once
// Text drawn into images (contact sheets, comparison sheets): UTF-8 laid out with FreeType from
// DejaVu Sans (Debian's fonts-dejavu-core), so captions keep the characters this field writes
// (σ, λ, ±, °, ×, ≤, –). A character the font lacks is drawn as the font's own missing-glyph box;
// bytes that are not well-formed UTF-8 draw U+FFFD.

#include <string_view>

#include "core/image.h"

namespace countershade {

// The advance width of `utf8` at `size_px` pixels per em, in pixels (rounded up).
int text_width(std::string_view utf8, int size_px);

// Draws `utf8` into `image` (1 to 4 channels; the first three take `colour`, a fourth is left as
// it is), its baseline at `baseline`, starting at `x`, each glyph's coverage blended over the
// pixels. What falls outside the image is clipped.
void draw_text(Image& image, int x, int baseline, std::string_view utf8, int size_px,
               const float colour[3]);

}  // namespace countershade
