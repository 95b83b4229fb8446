#include "render/procedural_texture.h"

#include <algorithm>
#include <glm/common.hpp>

#include "core/random.h"

namespace countershade {
namespace {

// A value in [−1, 1] for lattice point (i, j) of an octave.
double lattice(uint64_t seed, int octave, int i, int j) {
  const uint64_t key = (uint64_t(uint32_t(i)) << 32) | uint32_t(j);
  return 2.0 * double(mix64(seed ^ mix64(uint64_t(octave) * 0x9e3779b97f4a7c15ull ^ key)) >> 11) *
             0x1.0p-53 -
         1.0;
}

// Periodic value noise with `cells` cells per side, smoothly interpolated.
double value_noise(uint64_t seed, int octave, int cells, double u, double v) {
  const double x = u * cells, y = v * cells;
  const int i = int(x), j = int(y);
  const double tx = x - i, ty = y - j;
  const double sx = tx * tx * (3 - 2 * tx), sy = ty * ty * (3 - 2 * ty);
  auto at = [&](int a, int b) { return lattice(seed, octave, a % cells, b % cells); };
  return (1 - sy) * ((1 - sx) * at(i, j) + sx * at(i + 1, j)) +
         sy * ((1 - sx) * at(i, j + 1) + sx * at(i + 1, j + 1));
}

}  // namespace

TextureLevel checker_noise(const CheckerNoise& spec) {
  const int n = spec.size;
  TextureLevel level{n, n, std::vector<glm::vec3>(size_t(n) * size_t(n))};
  const glm::dvec3 light(0.62, 0.58, 0.48), dark(0.16, 0.18, 0.22);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const double u = (x + 0.5) / n, v = (y + 0.5) / n;
      double noise = 0, amplitude = 0.5;
      for (int octave = 0, cells = 4; octave < 5; ++octave, cells *= 2, amplitude *= 0.5)
        noise += amplitude * value_noise(spec.seed, octave, cells, u, v);
      noise /= 0.96875;  // the amplitudes' sum, so that |n| ≤ 1
      const bool is_light = ((x * spec.squares / n) + (y * spec.squares / n)) % 2 == 0;
      const glm::dvec3 albedo = (is_light ? light : dark) * (1.0 + spec.noise * noise);
      level.texels[size_t(y) * size_t(n) + size_t(x)] =
          glm::vec3(glm::clamp(albedo, glm::dvec3(0.0), glm::dvec3(1.0)));
    }
  return level;
}

TextureLevel stripes(const Stripes& spec) {
  const int n = spec.size;
  TextureLevel level{n, n, std::vector<glm::vec3>(size_t(n) * size_t(n))};
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      level.texels[size_t(y) * size_t(n) + size_t(x)] =
          glm::vec3(float((x * spec.stripes / n) % 2 ? spec.dark : spec.light));
  return level;
}

}  // namespace countershade
