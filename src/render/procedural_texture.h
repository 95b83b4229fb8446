#pragma once
// Textures the project makes itself, so that a stimulus needs no image file: a checkerboard with
// value noise over several octaves, which has content at every level of its mip pyramid (the
// receding ground plane of texture-space filtering), and stripes with edges at known places (an
// edge probe); docs/scene-format.md, "Procedural textures".

#include <cstdint>

#include "render/texture.h"

namespace countershade {

struct CheckerNoise {
  int size = 1024;      // texels per side (it tiles)
  int squares = 16;     // checker squares per side (even, so the pattern tiles)
  double noise = 0.35;  // relative amplitude of the noise on the albedo
  uint64_t seed = 1;
};

// Stripes across u (edges at u = k/stripes), alternately light and dark: the edge probe of
// "Scale against depth" (docs/enhancement-methods.md), whose edges lie at known world positions.
struct Stripes {
  int size = 1024;                  // texels per side
  int stripes = 16;                 // stripes across u (even, so the pattern tiles)
  double light = 0.6, dark = 0.15;  // grey albedos
};
TextureLevel stripes(const Stripes& spec);

// Linear RGB albedo in [0,1]: light and dark squares, each modulated by 1 + noise·n, with n the
// sum of five octaves of periodic value noise (cells of size/4 down to size/64), in [−1, 1].
TextureLevel checker_noise(const CheckerNoise& spec);

}  // namespace countershade
