#include "enhance/cornsweet_profile.h"

#include <cmath>

namespace countershade {

double CornsweetProfile::shape(double d) const {
  if (!power) return std::exp(-d / width);
  return d < width ? std::pow(1.0 - d / width, exponent) : 0.0;
}

PixelDoubles cornsweet_image_profile(const CornsweetProfile& profile, int width, int height) {
  PixelDoubles out(size_t(width) * size_t(height));
  const double centre = 0.5 * width;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double d = (x + 0.5) - centre;
      const double distance = profile.power ? std::abs(d) - 0.5 : std::abs(d);
      out[size_t(y) * size_t(width) + size_t(x)] = profile.at(distance, d > 0);
    }
  return out;
}

}  // namespace countershade
