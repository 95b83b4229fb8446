#include "enhance/lightness.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include <immintrin.h>

#include "core/code_quantizer.h"
#include "core/lightness_kernels.h"
#include "core/parallel.h"
#include "enhance/stimulus_noise.h"

namespace countershade {

std::vector<float> view_lightness(const View& view) {
  if (view.lightness.size() == view.lab.size()) return {view.lightness.begin(), view.lightness.end()};
  std::vector<float> L(view.lab.size());
  parallel_ranges(
      L.size(), 0,
      [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) L[i] = float(view.lab[i].L);
      },
      1 << 16);
  return L;
}

double display_lightness(const glm::dvec3& radiance, const Exposure& exposure) {
  return cielab_lightness(display_luminance(radiance, exposure));
}

namespace {

std::vector<float> radiance_lightness(const View& view) {
  const Image& radiance = view.render.radiance;
  const Exposure exposure = view.scene->display.exposure();
  std::vector<float> L(view.lab.size());
  parallel_ranges(
      L.size(), 0,
      [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) {
          const float* c = &radiance.pixels[3 * i];
          L[i] = float(display_lightness({c[0], c[1], c[2]}, exposure));
        }
      },
      1 << 14);
  return L;
}

}  // namespace

std::span<const float> view_signal_lightness(const View& view) {
  using Plane = std::vector<float>;
  const Image& radiance = view.render.radiance;
  if (view.scene && radiance.channels == 3 && radiance.pixels.size() == 3 * view.lab.size())
    return *view.memo.get<Plane>("signal_lightness", [&] { return std::make_shared<const Plane>(radiance_lightness(view)); });
  if (view.lightness.size() == view.lab.size()) return view.lightness;
  return *view.memo.get<Plane>("lightness", [&] { return std::make_shared<const Plane>(view_lightness(view)); });
}

Lab display_pixel_to_lab(const float* rgb, const DisplayEncoding& encoding) {
  return linear_rgb_to_lab({encoding.decode(rgb[0]), encoding.decode(rgb[1]), encoding.decode(rgb[2])});
}

namespace {

constexpr size_t kBlock = 64;

// Runs body(begin, end) over [0, n) in parallel, in ranges that start at multiples of kBlock, so
// that vectors of pixels keep their buffers' alignment, which the CIELAB conversion's streaming
// stores need. Each range's streaming stores are complete (sfence) before this returns.
void parallel_blocks(size_t n, int threads, const std::function<void(size_t, size_t)>& body) {
  parallel_ranges(
      (n + kBlock - 1) / kBlock, threads,
      [&](size_t begin, size_t end) {
        body(begin * kBlock, std::min(n, end * kBlock));
        _mm_sfence();
      },
      4096 / kBlock);
}

// Δ of the pixels [first, first + count) as LightnessChange defines it, the kind decided once per
// block; `signal`: the view's signal lightness (detail changes only).
void block_delta(const LightnessChange& change, const float* signal, size_t first, size_t count, double lambda,
                 double* delta) {
  if (change.kind == LightnessChange::Kind::detail) {  // no amount: its (empty) data may be null
    const double scale = lambda * change.factor;
    const float *s = signal + first, *smooth = change.smooth.data() + first;
    for (size_t k = 0; k < count; ++k) delta[k] = scale * (double(s[k]) - double(smooth[k]));
    return;
  }
  const double* amount = change.amount.data() + first;
  if (change.kind == LightnessChange::Kind::blended) {
    const float* weight = change.weight.data() + first;
    for (size_t k = 0; k < count; ++k) {  // in a loop that vectorises
      double alpha = lambda * double(weight[k]);
      alpha = alpha < 0.0 ? 0.0 : (alpha > 1.0 ? 1.0 : alpha);
      delta[k] = alpha * amount[k];
    }
  } else if (change.gain.empty()) {
    const double scale = lambda * change.factor;
    for (size_t k = 0; k < count; ++k) delta[k] = scale * amount[k];
  } else {
    const double* gain = change.gain.data() + first;
    for (size_t k = 0; k < count; ++k) delta[k] = (lambda * gain[k]) * amount[k];
  }
}

// Linear values of a channel's code values: a table when they are exact codes of `bits`.
class LinearDecoder {
 public:
  LinearDecoder(const DisplayEncoding& encoding, int bits) : encoding_(encoding) {
    if (bits <= 0 || bits > 16) return;
    levels_ = float((1u << bits) - 1u);
    table_.resize(size_t(levels_) + 1);
    for (size_t k = 0; k < table_.size(); ++k) table_[k] = encoding.decode(double(code_value(uint32_t(k))));
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
    int32_t code[3 * kBlock];
    if (!table_.empty() && count <= kBlock && exact_codes(rgb, 3 * count, levels_, code))
      return gather_planes(code, count, table_.data(), r, g, b);
    double* planes[3] = {r, g, b};
    for (size_t k = 0; k < count; ++k)
      for (int c = 0; c < 3; ++c) planes[c][k] = (*this)(rgb[3 * k + c]);
  }

 private:
  float code_value(uint32_t k) const { return float(k) / levels_; }  // the float a quantised pixel holds

  const DisplayEncoding& encoding_;
  float levels_ = 0;
  std::vector<double> table_;  // [code]: its linear value
};

}  // namespace

LabPixels display_to_lab(const Image& display, const DisplayEncoding& encoding, int bits, PixelVector* lightness) {
  const LinearDecoder decode(encoding, bits);
  LabPixels lab(size_t(display.width) * display.height);  // every element is written below
  if (lightness) lightness->resize(lab.size());
  float* plane = lightness ? lightness->data() : nullptr;
  parallel_blocks(
      lab.size(), 0,
      [&](size_t begin, size_t end) {
        alignas(64) double linear[3][kBlock];
        for (size_t first = begin; first < end; first += kBlock) {
          const size_t count = std::min(kBlock, end - first);
          decode.decode_rgb(display.pixels.data() + 3 * first, count, linear[0], linear[1], linear[2]);
          linear_to_lab_block(linear[0], linear[1], linear[2], count, lab.data() + first, plane ? plane + first : nullptr);
        }
      });
  return lab;
}

double mean_display_lightness(const Image& display, const DisplayEncoding& encoding, int bits) {
  const LinearDecoder decode(encoding, bits);
  PixelDoubles lightness(size_t(display.width) * display.height);  // every element is written below
  parallel_blocks(lightness.size(), 0, [&](size_t begin, size_t end) {
    alignas(64) double linear[3][kBlock];
    for (size_t first = begin; first < end; first += kBlock) {
      const size_t count = std::min(kBlock, end - first);
      decode.decode_rgb(display.pixels.data() + 3 * first, count, linear[0], linear[1], linear[2]);
      linear_to_lightness_block(linear[0], linear[1], linear[2], count, lightness.data() + first);
    }
  });
  double sum = 0;  // in pixel order, whatever the threads
  for (double L : lightness) sum += L;
  return lightness.empty() ? 0.0 : sum / double(lightness.size());
}

Composed compose_lightness(const View& view, const LightnessChange& change, double lambda, int threads,
                           const LightnessOffset* offset) {
  const CodeQuantizer& quantizer = CodeQuantizer::shared(view.encoding, view.bits);
  const LightnessComposer composer(quantizer, view.bits);
  Composed out;
  out.display = Image(view.width(), view.height(), 3, Image::Uninitialized{});  // every pixel is written below
  std::atomic<size_t> clipped{0};
  const float* in = view.display.pixels.data();
  const float* signal = change.kind == LightnessChange::Kind::detail ? view_signal_lightness(view).data() : nullptr;
  float* result = out.display.pixels.data();
  parallel_blocks(
      view.lab.size(), threads,
      [&](size_t begin, size_t end) {
        size_t local = 0;
        alignas(64) double delta[kBlock];
        for (size_t first = begin; first < end; first += kBlock) {
          const size_t count = std::min(kBlock, end - first);
          block_delta(change, signal, first, count, lambda, delta);
          if (offset)
            for (size_t i = 0; i < count; ++i) delta[i] += offset->offset * offset->where[first + i];
          local += composer.compose(view.lab.data() + first, in + 3 * first, delta, count, result + 3 * first);
        }
        clipped += local;
      });
  out.clipped_pixels = clipped;
  return out;
}

std::vector<std::pair<std::string, Image>> LightnessPrepared::auxiliary() const {
  std::vector<std::pair<std::string, Image>> out = auxiliary_;
  if (change_.kind == LightnessChange::Kind::detail) {
    Image smooth(view_->width(), view_->height(), 1, Image::Uninitialized{});
    smooth.pixels.assign(change_.smooth.begin(), change_.smooth.end());
    out.emplace_back("lightness_blurred", std::move(smooth));
  }
  return out;
}

std::vector<float> LightnessPrepared::mask() const {
  if (mask_) return mask_();
  if (change_.kind == LightnessChange::Kind::detail) return {change_.smooth.begin(), change_.smooth.end()};
  return {};
}

NoiseFunction plain_noise(const PrepareContext& context) {
  return [view = context.view, change = context.change_noise](double lambda) { return lambda_noise(*view, change, lambda); };
}

}  // namespace countershade
