#pragma once
// Display encoding: how linear, exposed radiance becomes the code values stored in a stimulus,
// and back. The inverse is what CIELAB conversions of stimuli use.

#include <algorithm>
#include <string>
#include <vector>

#include "core/image.h"

namespace countershade {

class DisplayEncoding {
 public:
  enum class Kind { srgb, gamma, lut };

  static DisplayEncoding srgb();
  static DisplayEncoding gamma(double exponent);
  // A measured table: code values in [0,1] and the relative luminance each produces, both
  // strictly increasing, first row (0, 0) and last row (1, 1) after normalisation.
  static DisplayEncoding lut(std::vector<double> codes, std::vector<double> luminances);

  Kind kind() const { return kind_; }
  // A table's rows, normalised to [0, 1] (empty for the other kinds).
  const std::vector<double>& lut_codes() const { return codes_; }
  const std::vector<double>& lut_luminances() const { return luminances_; }
  double gamma_exponent() const { return gamma_; }
  std::string describe() const;
  bool operator==(const DisplayEncoding& other) const = default;

  // Linear relative luminance in [0,1] (clamped) -> code value in [0,1].
  double encode(double linear) const;
  // Code value in [0,1] -> linear relative luminance.
  double decode(double code) const;

 private:
  Kind kind_ = Kind::srgb;
  double gamma_ = 2.2;
  std::vector<double> codes_, luminances_;
};

// How linear radiance becomes the display's linear light, per channel: scaled by the exposure
// (2^stops), clamped to full scale, and lifted by the black level, the share of full scale that
// radiance 0 shows. A black level leaves an enhancement room below the image's darkest pixel, as
// the exposure leaves it room above the brightest (an experiment's "headroom").
struct Exposure {
  double scale = 1.0;
  double black = 0.0;
  double operator()(double radiance) const {
    return black + (1.0 - black) * std::clamp(radiance * scale, 0.0, 1.0);
  }
};

// Exposure and display encoding, per channel: linear radiance -> code values in [0,1].
Image encode_for_display(const Image& radiance, const Exposure& exposure,
                         const DisplayEncoding& encoding);

}  // namespace countershade
