#include "enhance/lightness.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "core/code_quantizer.h"
#include "core/lightness_kernels.h"
#include "core/parallel.h"
#include "enhance/pixel_blocks.h"
#include "enhance/stimulus_noise.h"

namespace countershade {

std::vector<float> view_lightness(const View& view) {
  if (view.lightness.size() == view.lab.size())
    return {view.lightness.begin(), view.lightness.end()};
  std::vector<float> L(view.lab.size());
  parallel_ranges(
      L.size(), 0,
      [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) L[i] = float(view.lab[i].L);
      },
      1 << 16);
  return L;
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
    return *view.memo.get<Plane>("signal_lightness", [&] {
      return std::make_shared<const Plane>(radiance_lightness(view));
    });
  if (view.lightness.size() == view.lab.size()) return view.lightness;
  return *view.memo.get<Plane>("lightness",
                               [&] { return std::make_shared<const Plane>(view_lightness(view)); });
}

namespace {

// Δ of the pixels [first, first + count) as LightnessChange defines it, the kind decided once per
// block; `signal`: the view's signal lightness (detail changes only).
void block_delta(const LightnessChange& change, const float* signal, size_t first, size_t count,
                 double lambda, double* delta) {
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

}  // namespace

Composed compose_lightness(const View& view, const LightnessChange& change, double lambda,
                           int threads, const LightnessOffset* offset) {
  const CodeQuantizer& quantizer = CodeQuantizer::shared(view.encoding, view.bits);
  const LightnessComposer composer(quantizer, view.bits);
  Composed out;
  out.display = Image(view.width(), view.height(), 3,
                      Image::Uninitialized{});  // every pixel is written below
  std::atomic<size_t> clipped{0};
  const float* in = view.display.pixels.data();
  const float* signal =
      change.kind == LightnessChange::Kind::detail ? view_signal_lightness(view).data() : nullptr;
  float* result = out.display.pixels.data();
  parallel_pixel_blocks(view.lab.size(), threads, [&](size_t begin, size_t end) {
    size_t local = 0;
    alignas(64) double delta[kPixelBlock];
    for (size_t first = begin; first < end; first += kPixelBlock) {
      const size_t count = std::min(kPixelBlock, end - first);
      block_delta(change, signal, first, count, lambda, delta);
      if (offset)
        for (size_t i = 0; i < count; ++i) delta[i] += offset->offset * offset->where[first + i];
      local += composer.compose(view.lab.data() + first, in + 3 * first, delta, count,
                                result + 3 * first);
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
  if (change_.kind == LightnessChange::Kind::detail)
    return {change_.smooth.begin(), change_.smooth.end()};
  return {};
}

NoiseFunction plain_noise(const PrepareContext& context) {
  return [view = context.view, change = context.change_noise](double lambda) {
    return lambda_noise(*view, change, lambda);
  };
}

}  // namespace countershade
