#pragma once
// Reading a per-pixel field of the view at the film position a shading point projects to.

#include <algorithm>
#include <cmath>
#include <glm/vec2.hpp>
#include <utility>
#include <vector>

namespace countershade {

// Bilinear interpolation at `film` (pixels; pixel x covers [x, x+1)) over the pixels of `mask`
// among the four nearest: the weighted sum of `value(i)` and the sum of the weights used (0 when
// none of the four is in the mask), so a field never mixes with pixels outside the object.
template <class T, class Value>
std::pair<T, double> interpolate_in_mask(const glm::dvec2& film, int width, int height,
                                         const std::vector<char>& mask, Value value) {
  const double fx = film.x - 0.5, fy = film.y - 0.5;
  const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
  const double tx = fx - x0, ty = fy - y0;
  T sum{};
  double weight = 0;
  for (int dy = 0; dy < 2; ++dy)
    for (int dx = 0; dx < 2; ++dx) {
      const int x = std::clamp(x0 + dx, 0, width - 1), y = std::clamp(y0 + dy, 0, height - 1);
      const size_t i = size_t(y) * size_t(width) + size_t(x);
      if (!mask[i]) continue;
      const double w = (dx ? tx : 1 - tx) * (dy ? ty : 1 - ty);
      sum += w * value(i);
      weight += w;
    }
  return {sum, weight};
}

}  // namespace countershade
