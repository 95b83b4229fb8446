#pragma once
// A texture filtered in texture space (docs/methods.md, "Texture-space filtering"):
// - `texture` mode filters level 0 and builds the pyramid of the result by box filtering;
// - `mip` mode filters every level of the plain pyramid on its own, with σ in that level's texels,
//   so the kernel keeps about the same size on the screen while it stays on the surface.
// What does not depend on λ (the change of L* per unit λ, per level) is computed once per
// (texture, filter, σ) and cached on disk under a hash of those inputs; a λ then costs one
// pass over the texels.

#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "enhance/lightness_filters.h"
#include "render/texture.h"

namespace countershade {

enum class TextureMode { texture, mip };

// The L* of every texel of a level (CIELAB of its linear RGB, white = 1).
std::vector<float> level_lightness(const TextureLevel& level);

// The level with L* changed by strength·detail, lightness-only (a*, b* scaled with L*, as every
// lightness method composes), clamped to reflectances in [0,1]. A texel whose change is 0 keeps
// its value bit for bit.
TextureLevel with_detail(const TextureLevel& plain, const std::vector<float>& detail,
                         double strength);
// One texel of it: `plain` with its L* changed by `change`.
glm::vec3 texel_with_detail(const glm::vec3& plain, double change);

struct FilteredPyramid {
  std::shared_ptr<const Texture> plain;
  TextureMode mode = TextureMode::mip;
  std::vector<std::vector<float>> detail;  // [level][texel]: one level in texture mode, all in mip
  std::vector<double>
      level_strengths;  // mip: strength multiplier per level (the last repeats); empty: all 1

  double strength_of_level(size_t level) const;
  // The filtered texture at strength λ (λ = 0: the plain pyramid's texels).
  Texture at(double lambda) const;
  // A grey pyramid of the change of L* per unit λ over (the texel's L* + 16): a texel's change d
  // moves the L* of the light it reflects by about d·(L* + 16)/(L*_texel + 16) (the pixel pass's
  // change per λ for the noise budget). Texture mode: level 0's, box filtered.
  Texture relative_detail() const;
  // The texel of `at(lambda)` at (level, index), in mip mode (each level on its own).
  glm::vec3 mip_texel_at(double lambda, size_t level, size_t index) const;
};

// Where filtered pyramids are cached: $COUNTERSHADE_CACHE, else $XDG_CACHE_HOME/countershade,
// else ~/.cache/countershade; none when no such folder can be made.
std::optional<std::filesystem::path> pyramid_cache_folder();

// Filters `plain` (reading and writing the cache in `cache` when given).
FilteredPyramid filter_pyramid(std::shared_ptr<const Texture> plain, TextureMode mode,
                               const LightnessFilter& filter, std::vector<double> level_strengths,
                               const std::optional<std::filesystem::path>& cache, int threads = 0);

}  // namespace countershade
