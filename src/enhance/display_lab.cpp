#include "enhance/display_lab.h"

#include <algorithm>
#include <cstdint>

#include "core/lightness_kernels.h"
#include "enhance/pixel_blocks.h"
#include "render/render_types.h"

namespace countershade {

double display_lightness(const glm::dvec3& radiance, const Exposure& exposure) {
  return cielab_lightness(display_luminance(radiance, exposure));
}

Lab display_pixel_to_lab(const float* rgb, const DisplayEncoding& encoding) {
  return linear_rgb_to_lab(
      {encoding.decode(rgb[0]), encoding.decode(rgb[1]), encoding.decode(rgb[2])});
}

namespace {

// Linear values of a channel's code values: a table when they are exact codes of `bits`.
class LinearDecoder {
 public:
  LinearDecoder(const DisplayEncoding& encoding, int bits) : encoding_(encoding) {
    if (bits <= 0 || bits > 16) return;
    levels_ = float((1u << bits) - 1u);
    table_.resize(size_t(levels_) + 1);
    for (size_t k = 0; k < table_.size(); ++k)
      table_[k] = encoding.decode(double(code_value(uint32_t(k))));
  }
  double operator()(float v) const {
    if (!table_.empty() && v >= 0.0f && v <= 1.0f) {
      const uint32_t k = uint32_t(v * levels_ + 0.5f);
      if (code_value(k) == v) return table_[k];
    }
    return encoding_.decode(v);
  }

  // The linear values of `count` RGB pixels, one plane per channel. When every value is an exact
  // code (the usual case) the codes are found in one loop that vectorises and read from the table.
  void decode_rgb(const float* rgb, size_t count, double* r, double* g, double* b) const {
    int32_t code[3 * kPixelBlock];
    if (!table_.empty() && count <= kPixelBlock && exact_codes(rgb, 3 * count, levels_, code))
      return gather_planes(code, count, table_.data(), r, g, b);
    double* planes[3] = {r, g, b};
    for (size_t k = 0; k < count; ++k)
      for (int c = 0; c < 3; ++c) planes[c][k] = (*this)(rgb[3 * k + c]);
  }

 private:
  float code_value(uint32_t k) const {
    return float(k) / levels_;
  }  // the float a quantised pixel holds

  const DisplayEncoding& encoding_;
  float levels_ = 0;
  std::vector<double> table_;  // [code]: its linear value
};

}  // namespace

LabPixels display_to_lab(const Image& display, const DisplayEncoding& encoding, int bits,
                         PixelVector* lightness) {
  const LinearDecoder decode(encoding, bits);
  LabPixels lab(size_t(display.width) * display.height);  // every element is written below
  if (lightness) lightness->resize(lab.size());
  float* plane = lightness ? lightness->data() : nullptr;
  parallel_pixel_blocks(lab.size(), 0, [&](size_t begin, size_t end) {
    alignas(64) double linear[3][kPixelBlock];
    for (size_t first = begin; first < end; first += kPixelBlock) {
      const size_t count = std::min(kPixelBlock, end - first);
      decode.decode_rgb(display.pixels.data() + 3 * first, count, linear[0], linear[1], linear[2]);
      linear_to_lab_block(linear[0], linear[1], linear[2], count, lab.data() + first,
                          plane ? plane + first : nullptr);
    }
  });
  return lab;
}

double mean_display_lightness(const Image& display, const DisplayEncoding& encoding, int bits) {
  const LinearDecoder decode(encoding, bits);
  PixelDoubles lightness(size_t(display.width) * display.height);  // every element is written below
  parallel_pixel_blocks(lightness.size(), 0, [&](size_t begin, size_t end) {
    alignas(64) double linear[3][kPixelBlock];
    for (size_t first = begin; first < end; first += kPixelBlock) {
      const size_t count = std::min(kPixelBlock, end - first);
      decode.decode_rgb(display.pixels.data() + 3 * first, count, linear[0], linear[1], linear[2]);
      linear_to_lightness_block(linear[0], linear[1], linear[2], count, lightness.data() + first);
    }
  });
  double sum = 0;  // in pixel order, whatever the threads
  for (double L : lightness) sum += L;
  return lightness.empty() ? 0.0 : sum / double(lightness.size());
}

}  // namespace countershade
