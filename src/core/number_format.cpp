#include "core/number_format.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace countershade {

std::string format_value(double v) {
  if (std::abs(v) < 1e-12) v = 0;
  char buffer[32];
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(buffer, sizeof buffer, "%.*g", precision, v);
    if (std::abs(std::strtod(buffer, nullptr) - v) <= 1e-12 * std::max(1.0, std::abs(v))) break;
  }
  return buffer;
}

double round_to(double v, int decimals) {
  const double scale = std::pow(10.0, decimals);
  return std::round(v * scale) / scale;
}

}  // namespace countershade
