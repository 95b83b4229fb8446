#include "observer/contrast_sensitivity.h"

#include <cmath>

namespace countershade::observer {
namespace {

double sech(double x) { return 1.0 / std::cosh(x); }

// The oblique effect's corner frequency and the scale of its fall above it, in cycles per degree.
constexpr double kObliqueCorner = 3.48, kObliqueScale = 13.57;

}  // namespace

double sso_sensitivity(double f) {
  return 373.08 * (sech(std::pow(f / 4.1726, 0.7786)) - 0.8493 * sech(f / 1.3625));
}

double oblique_gain(double f, double theta) {
  if (f <= kObliqueCorner) return 1.0;
  const double s = std::sin(2 * theta);
  return 1.0 - (1.0 - std::exp(-(f - kObliqueCorner) / kObliqueScale)) * s * s;
}

}  // namespace countershade::observer
