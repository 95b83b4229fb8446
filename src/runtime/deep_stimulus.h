#pragma once
// 16-bit stimuli on screen: each code's high and low bytes in the two halves of an 8-bit texture,
// drawn at 1:1 by a shader that joins them and quantises each pixel for the framebuffer, exactly
// as runtime/fine_levels.h defines it (the nearest 10-bit level, or the seeded dither to 8 bits).
// The bytes keep the 16-bit codes exact up to the shader, so its output is reproducible to the bit
// and testable against the C++ reference.

#include <cstdint>
#include <vector>

#include "runtime/fine_levels.h"

namespace countershade::runtime {

// Where a stimulus goes: its top-left pixel in framebuffer pixels from the top-left, its size,
// and the framebuffer's height (OpenGL counts rows from the bottom).
struct PixelRect {
  int x = 0, y = 0, width = 0, height = 0;
  int framebuffer_height = 0;
};

// A new texture, bound, sampled nearest-neighbour at one level and clamped at its edges: stimuli
// are shown at 1:1, never filtered.
unsigned new_nearest_texture();

class DeepStimulusRenderer {
 public:
  // Needs a current OpenGL 3.3 core context; throws std::runtime_error when the shader fails.
  DeepStimulusRenderer();
  ~DeepStimulusRenderer();
  DeepStimulusRenderer(const DeepStimulusRenderer&) = delete;
  DeepStimulusRenderer& operator=(const DeepStimulusRenderer&) = delete;

  // A 16-bit RGBA image (rows top to bottom) as an 8-bit texture twice its height, the high bytes
  // above the low ones; the caller deletes it.
  static unsigned upload(const std::vector<uint16_t>& rgba, int width, int height);

  // Draws the texture into the bound draw framebuffer through `path` (ten_bit or dither); `frame`
  // and `seed` choose the dither pattern. Leaves the viewport at the whole framebuffer.
  void draw(unsigned texture, const PixelRect& where, OutputPath path, uint32_t frame,
            uint32_t seed) const;

 private:
  struct Program {
    unsigned id = 0;
    int top_left = -1, frame = -1, seed_mix = -1;
  };
  static Program link(int mode);  // the program of one path (kFragmentMain's MODE)

  Program programs_[3];
  unsigned vertex_array_ = 0;
};

// The bound read framebuffer's pixels in `where`, as 16-bit RGBA (rows top to bottom). A channel
// of b bits reads back as its level × 65535 / (2^b − 1), rounded.
std::vector<uint16_t> read_back_rgba16(const PixelRect& where);

// The test pattern of the read-back check: every 10-bit level, and each one 31 codes above and
// below it (still the same level), as a 256 × 12 RGBA image.
std::vector<uint16_t> ten_bit_probe(int* width, int* height);

// Draws the probe through the ten-bit path into the bound framebuffer (its top-left corner) and
// reads it back: true when every pixel holds its own 10-bit level. On an 8-bit framebuffer it
// cannot. The framebuffer must be at least 256 × 12 pixels; what was drawn is left there.
bool ten_bit_read_back_holds(const DeepStimulusRenderer& renderer, int framebuffer_height);

}  // namespace countershade::runtime
