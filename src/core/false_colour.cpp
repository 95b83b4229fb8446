#include "core/false_colour.h"

#include <algorithm>
#include <cmath>

namespace countershade {
namespace {

// Viridis at nine evenly spaced points, as 8-bit sRGB; linear interpolation between them.
constexpr unsigned char kViridis[9][3] = {{68, 1, 84},    {72, 40, 120},  {62, 73, 137},
                                          {49, 104, 142}, {38, 130, 142}, {31, 158, 137},
                                          {53, 183, 121}, {110, 206, 88}, {253, 231, 37}};

}  // namespace

void false_colour(double t, float* rgb) {
  if (std::isnan(t)) {
    rgb[0] = rgb[1] = rgb[2] = 0.0f;
    return;
  }
  const double position = std::clamp(t, 0.0, 1.0) * 8.0;
  const int k = std::min(7, int(position));
  const double f = position - k;
  for (int c = 0; c < 3; ++c)
    rgb[c] = float(((1 - f) * kViridis[k][c] + f * kViridis[k + 1][c]) / 255.0);
}

Image false_colour_image(const Image& values) {
  Image out(values.width, values.height, 3);
  for (size_t i = 0; i < size_t(values.width) * values.height; ++i)
    false_colour(values.pixels[i * size_t(values.channels)], &out.pixels[3 * i]);
  return out;
}

}  // namespace countershade
