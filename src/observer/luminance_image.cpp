#include "observer/luminance_image.h"

#include <cmath>
#include <vector>

#include "core/error.h"
#include "core/image.h"

namespace countershade::observer {
namespace {

constexpr double kRec709[3] = {0.2126, 0.7152, 0.0722};

// The luminance of every code of a `bits`-deep file on the display: one decode per code rather
// than one per pixel and channel (the transfer functions are pow-heavy, and a set has hundreds of
// images).
std::vector<double> code_luminances(const CalibratedDisplay& display, int bits) {
  const size_t codes = size_t(1) << bits;
  std::vector<double> table(codes);
  for (size_t c = 0; c < codes; ++c) table[c] = display.luminance(double(c) / double(codes - 1));
  return table;
}

// How a file's values become luminance: through the display's table of codes (files of up to 16
// bits), through the display itself (deeper integer files), or as they are (float files).
struct CodeDecoder {
  const CalibratedDisplay* display = nullptr;
  std::vector<double> table;
  double operator()(double v) const {
    if (!table.empty()) return table[size_t(std::lround(v * double(table.size() - 1)))];
    return display ? display->luminance(v) : v;
  }
};

// Luminance of a pixel: its channels decoded and weighted.
double luminance(const Image& image, int x, int y, const CodeDecoder& decode) {
  const auto linear = [&](int c) { return decode(image.at(x, y, c)); };
  if (image.channels < 3) return linear(0);
  return kRec709[0] * linear(0) + kRec709[1] * linear(1) + kRec709[2] * linear(2);
}

}  // namespace

CalibratedDisplay srgb_display(double peak) { return {DisplayEncoding::srgb(), 0, peak}; }

LuminanceImage read_luminance(const std::string& path, const CalibratedDisplay& display) {
  int bits = 0;
  const Image image = read_image(path, &bits);
  // Integer files hold display codes; float files luminance.
  CodeDecoder decode;
  if (bits != 0) decode.display = &display;
  if (bits != 0 && bits <= 16) decode.table = code_luminances(display, bits);
  LuminanceImage out{image.width, image.height, {}};
  out.cd_m2.reserve(size_t(image.width) * size_t(image.height));
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const double l = luminance(image, x, y, decode);
      if (!(l >= 0) || !std::isfinite(l))
        throw_input_error(path, "pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                                    ") has no finite, non-negative luminance");
      out.cd_m2.push_back(l);
    }
  return out;
}

ContrastImage contrast_between(const LuminanceImage& reference, const LuminanceImage& test,
                               const std::string& reference_name, const std::string& test_name) {
  if (test.width != reference.width || test.height != reference.height)
    throw_input_error(test_name, "the image is " + std::to_string(test.width) + "x" +
                                     std::to_string(test.height) + " but the reference is " +
                                     std::to_string(reference.width) + "x" +
                                     std::to_string(reference.height));
  double mean = 0;
  for (double l : reference.cd_m2) mean += l;
  mean /= double(reference.cd_m2.size());
  if (!(mean > 0)) throw_input_error(reference_name, "the reference is black (mean luminance 0)");
  ContrastImage contrast(reference.width, reference.height);
  for (size_t i = 0; i < contrast.values.size(); ++i)
    contrast.values[i] = (test.cd_m2[i] - reference.cd_m2[i]) / mean;
  return contrast;
}

}  // namespace countershade::observer
