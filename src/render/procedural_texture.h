#pragma once
// Textures the project makes itself, so that a stimulus needs no image file: a checkerboard with
// value noise over several octaves, which has content at every level of its mip pyramid (the
// receding ground plane of texture-space filtering; docs/scene-format.md, "Procedural textures").

#include <cstdint>

#include "render/texture.h"

namespace countershade {

struct CheckerNoise {
  int size = 1024;       // texels per side (it tiles)
  int squares = 16;      // checker squares per side (even, so the pattern tiles)
  double noise = 0.35;   // relative amplitude of the noise on the albedo
  uint64_t seed = 1;
};

// Linear RGB albedo in [0,1]: light and dark squares, each modulated by 1 + noise·n, with n the
// sum of five octaves of periodic value noise (cells of size/4 down to size/64), in [−1, 1].
TextureLevel checker_noise(const CheckerNoise& spec);

}  // namespace countershade
