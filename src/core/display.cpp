#include "core/display.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/color.h"
#include "core/error.h"

namespace countershade {
namespace {

// Piecewise-linear interpolation of y(x) over a strictly increasing x table.
double interpolate(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  if (x <= xs.front()) return ys.front();
  if (x >= xs.back()) return ys.back();
  auto it = std::upper_bound(xs.begin(), xs.end(), x);
  size_t i = size_t(it - xs.begin());
  double t = (x - xs[i - 1]) / (xs[i] - xs[i - 1]);
  return ys[i - 1] + t * (ys[i] - ys[i - 1]);
}

}  // namespace

DisplayEncoding DisplayEncoding::srgb() { return {}; }

DisplayEncoding DisplayEncoding::gamma(double exponent) {
  if (!(exponent > 0.0) || !std::isfinite(exponent))
    throw InputError("gamma exponent must be a positive number");
  DisplayEncoding e;
  e.kind_ = Kind::gamma;
  e.gamma_ = exponent;
  return e;
}

DisplayEncoding DisplayEncoding::lut(std::vector<double> codes, std::vector<double> luminances) {
  if (codes.size() < 2 || codes.size() != luminances.size())
    throw InputError("lookup table needs at least two (code, luminance) rows");
  for (size_t i = 0; i < codes.size(); ++i) {
    if (!std::isfinite(codes[i]) || !std::isfinite(luminances[i]))
      throw InputError("lookup table row " + std::to_string(i + 1) + " is not a finite number");
    if (i > 0 && (codes[i] <= codes[i - 1] || luminances[i] <= luminances[i - 1]))
      throw InputError("lookup table row " + std::to_string(i + 1) +
                       ": code and luminance must both increase strictly");
  }
  // Normalise both axes to [0,1] so the table describes relative luminance.
  auto normalise = [](std::vector<double>& v) {
    double lo = v.front(), hi = v.back();
    for (double& x : v) x = (x - lo) / (hi - lo);
  };
  normalise(codes);
  normalise(luminances);
  DisplayEncoding e;
  e.kind_ = Kind::lut;
  e.codes_ = std::move(codes);
  e.luminances_ = std::move(luminances);
  return e;
}

std::string DisplayEncoding::describe() const {
  std::ostringstream s;
  switch (kind_) {
    case Kind::srgb:
      s << "srgb";
      break;
    case Kind::gamma:
      s << "gamma " << gamma_;
      break;
    case Kind::lut:
      s << "lut (" << codes_.size() << " rows)";
      break;
  }
  return s.str();
}

double DisplayEncoding::encode(double linear) const {
  linear = std::isnan(linear) ? 0.0 : std::clamp(linear, 0.0, 1.0);
  switch (kind_) {
    case Kind::srgb:
      return srgb_encode(linear);
    case Kind::gamma:
      return std::pow(linear, 1.0 / gamma_);
    case Kind::lut:
      return interpolate(luminances_, codes_, linear);
  }
  return 0.0;
}

double DisplayEncoding::decode(double code) const {
  code = std::clamp(code, 0.0, 1.0);
  switch (kind_) {
    case Kind::srgb:
      return srgb_decode(code);
    case Kind::gamma:
      return std::pow(code, gamma_);
    case Kind::lut:
      return interpolate(codes_, luminances_, code);
  }
  return 0.0;
}

Image encode_for_display(const Image& radiance, const Exposure& exposure,
                         const DisplayEncoding& encoding) {
  Image out(radiance.width, radiance.height, radiance.channels, Image::Uninitialized{});
  for (size_t i = 0; i < radiance.pixels.size(); ++i)
    out.pixels[i] = float(encoding.encode(exposure(radiance.pixels[i])));
  return out;
}

}  // namespace countershade
