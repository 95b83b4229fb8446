#pragma once
// Image textures as mip pyramids (docs/methods.md, "Texture-space filtering").
//
// Level 0 holds the texels as loaded; each further level halves the size (rounded down, at least
// 1) by box filtering, down to 1×1. A lookup with no footprint reads level 0 bilinearly, as a
// texture without a pyramid would; a lookup with the footprint of a pixel (the UV derivatives
// from ray differentials) picks the level whose texels are about a pixel wide and blends the two
// nearest levels (trilinear filtering), with several such probes along the footprint where it is
// elongated. Where a texture is magnified the level is 0 and one probe, so the plain render
// changes only where textures are minified.

#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "core/image.h"

namespace countershade {

// One level: linear RGB, top row first, wrapping at the borders.
struct TextureLevel {
  int width = 0, height = 0;
  std::vector<glm::vec3> texels;

  const glm::vec3& at(int x, int y) const { return texels[size_t(y) * size_t(width) + size_t(x)]; }
  // Bilinear lookup with wrap-around; v = 0 is the bottom row.
  glm::dvec3 bilinear(const glm::dvec2& uv) const;
};

// One texel a lookup reads, and its weight in the result.
struct TextureTap {
  uint32_t level = 0, texel = 0;  // texel: y·width + x in that level
  double weight = 0;
};

// A level from an image's first three channels (one channel: grey), decoded from sRGB or taken as
// linear values; and back to a linear 3-channel float image.
TextureLevel level_from_image(const Image& image, bool srgb_encoded);
Image image_from_level(const TextureLevel& level);

// The next coarser level: max(1, ⌊w/2⌋) × max(1, ⌊h/2⌋), each texel the area-weighted mean of the
// finer texels it covers (exactly the 2×2 mean where the finer size is even).
TextureLevel downsample(const TextureLevel& finer);

class Texture {
 public:
  Texture() = default;
  // The pyramid of `base`, built by box filtering.
  explicit Texture(TextureLevel base);
  // A pyramid made elsewhere (e.g. filtered level by level); levels[0] is the finest, and each
  // must have the size downsample() would give.
  static Texture from_levels(std::vector<TextureLevel> levels);

  int width() const { return levels_.front().width; }
  int height() const { return levels_.front().height; }
  const std::vector<TextureLevel>& levels() const { return levels_; }

  // Level 0, bilinear (no footprint).
  glm::dvec3 sample(const glm::dvec2& uv) const { return levels_.front().bilinear(uv); }
  // Filtered lookup for a footprint given by the UV derivatives along the film's x and y: up to
  // kMaxAnisotropy trilinear probes spread along the footprint's longer axis, each at the level
  // whose texels match the footprint's width per probe (GPU-style anisotropic filtering, so that
  // textures seen at grazing angles are not blurred along their shorter axis too).
  glm::dvec3 sample(const glm::dvec2& uv, const glm::dvec2& duv_dx, const glm::dvec2& duv_dy) const;
  // The texels that lookup reads, appended to `out` with weights summing to 1: sample() is
  // Σ weight·texel up to rounding (a texel may appear more than once).
  void taps(const glm::dvec2& uv, const glm::dvec2& duv_dx, const glm::dvec2& duv_dy,
            std::vector<TextureTap>& out) const;
  // The (fractional) level of that lookup: log2 of the width each probe covers in level-0 texels
  // (the longer side over the number of probes, at least the shorter side), clamped to
  // [0, levels − 1].
  double level_of(const glm::dvec2& duv_dx, const glm::dvec2& duv_dy) const;
  // The number of probes: the footprint's longer side over its shorter, rounded, at most
  // kMaxAnisotropy (1 where the texture is magnified).
  int probes_of(const glm::dvec2& duv_dx, const glm::dvec2& duv_dy) const;

  static constexpr int kMaxAnisotropy = 8;

 private:
  // The probes, their level and the axis they spread along, for one footprint.
  struct Footprint {
    int probes = 1;
    double level = 0;
    glm::dvec2 axis{0.0};
  };
  Footprint footprint(const glm::dvec2& duv_dx, const glm::dvec2& duv_dy) const;
  glm::dvec3 trilinear(const glm::dvec2& uv, double level) const;
  void trilinear_taps(const glm::dvec2& uv, double level, double weight,
                      std::vector<TextureTap>& out) const;

  std::vector<TextureLevel> levels_{TextureLevel{1, 1, {glm::vec3(0.0f)}}};
};

}  // namespace countershade
