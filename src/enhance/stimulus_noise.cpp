#include "enhance/stimulus_noise.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include "core/code_quantizer.h"
#include "core/color.h"
#include "core/display.h"

namespace countershade {
namespace {

constexpr double kTableMax = 4.0;  // beyond, the large-r form is exact to 1e-9
constexpr int kTableSteps = 1024;

// E[(Q(x + d) − Q(x))²] / q² for x uniform over a step and |d| = (m + f)·q: the values differ
// by m steps with probability 1 − f and by m + 1 with probability f.
double rounded_square(double steps) {
  const double m = std::floor(steps), f = steps - m;
  return m * m * (1.0 - f) + (m + 1.0) * (m + 1.0) * f;
}

// Half the mean of rounded_square over d ~ N(0, 2r²) (d the difference of two errors), by
// Simpson's rule over [0, 12·sd] of the half-normal density.
double mean_rounded_square(double r) {
  if (r <= 0) return 0.0;
  const double sd = std::sqrt(2.0) * r, upper = 12.0 * sd;
  constexpr int n = 4096;
  const double h = upper / n;
  double sum = 0;
  for (int i = 0; i <= n; ++i) {
    const double d = i * h;
    const double weight = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    sum += weight * rounded_square(d) * std::exp(-0.5 * (d / sd) * (d / sd));
  }
  const double density = 2.0 / (sd * std::sqrt(2.0 * M_PI));  // half-normal
  return 0.5 * sum * h / 3.0 * density;
}

// mean_rounded_square at kTableMax·i/kTableSteps, each entry computed when first read: an entry
// costs 4,097 exponentials, the whole table 30 ms (over a second under an emulated processor),
// and a small image reads a few hundred entries. Threads that race for an entry compute the same
// value; NaN marks one not yet computed.
class QuantizedTable {
 public:
  QuantizedTable() {
    for (auto& entry : entries_) entry.store(std::numeric_limits<double>::quiet_NaN());
  }
  double operator[](int i) {
    double value = entries_[size_t(i)].load(std::memory_order_relaxed);
    if (std::isnan(value)) {
      value = mean_rounded_square(kTableMax * i / kTableSteps);
      entries_[size_t(i)].store(value, std::memory_order_relaxed);
    }
    return value;
  }

 private:
  std::array<std::atomic<double>, kTableSteps + 1> entries_;
};

// L* of a pixel of code values and the L* step of one code of each channel (central where both
// neighbours exist).
struct CodeSteps {
  double step[3];
  bool grey;  // all channels hold the same code: their rounding errors are one error
};

class CodeLightness {
 public:
  CodeLightness(const DisplayEncoding& encoding, int bits)
      : levels_((1u << bits) - 1u), linear_(levels_ + 1) {
    for (uint32_t k = 0; k <= levels_; ++k) linear_[k] = encoding.decode(double(k) / levels_);
  }
  uint32_t code(float value) const {
    return uint32_t(std::lround(std::clamp(double(value), 0.0, 1.0) * levels_));
  }

  CodeSteps steps(const uint32_t k[3]) const {
    const auto& w = color_constants::kRgbToXyz[1];
    double y = 0;
    for (int c = 0; c < 3; ++c) y += w[c] * linear_[k[c]];
    CodeSteps out{{0, 0, 0}, k[0] == k[1] && k[1] == k[2]};
    for (int c = 0; c < 3; ++c) {
      const uint32_t lo = k[c] > 0 ? k[c] - 1 : k[c], hi = k[c] < levels_ ? k[c] + 1 : k[c];
      if (hi == lo) continue;
      const double up = cielab_lightness(y + w[c] * (linear_[hi] - linear_[k[c]]));
      const double down = cielab_lightness(std::max(y - w[c] * (linear_[k[c]] - linear_[lo]), 0.0));
      out.step[c] = (up - down) / double(hi - lo);
    }
    return out;
  }

 private:
  uint32_t levels_;
  std::vector<double> linear_;
};

// The L* step of the pixel's rounding: channels rounded alike add up, others add in quadrature.
double lightness_step(const CodeSteps& s) {
  if (s.grey) return std::abs(s.step[0] + s.step[1] + s.step[2]);
  return std::sqrt(s.step[0] * s.step[0] + s.step[1] * s.step[1] + s.step[2] * s.step[2]);
}

// lightness_step of each pixel's codes, remembered for the last codes seen in each of 4096 slots:
// neighbouring pixels mostly hold the same codes, and a step costs six cube roots.
class StepCache {
 public:
  explicit StepCache(const CodeLightness& codes)
      : codes_(codes), slots_(kSlots, {UINT64_MAX, 0.0}) {}
  double operator()(const float* rgb) {
    uint32_t k[3];
    for (int c = 0; c < 3; ++c) k[c] = codes_.code(rgb[c]);
    const uint64_t key = code_triple_key(k[0], k[1], k[2]);
    auto& slot = slots_[size_t((key * 0x9E3779B97F4A7C15ull) >> 52)];
    if (slot.first != key) slot = {key, lightness_step(codes_.steps(k))};
    return slot.second;
  }

 private:
  static constexpr size_t kSlots = 4096;  // the hash's top 12 bits
  const CodeLightness& codes_;
  std::vector<std::pair<uint64_t, double>> slots_;
};

// The x at which P(|e| > x), averaged over pixels, is 1 %, on a histogram of σ. The share falls
// with x and is convex, so Newton steps from below converge to it without overshooting; a step
// that leaves the bracket (rounding near the root) is a bisection instead.
double ninety_ninth_percentile(const std::vector<float>& sigma, double largest) {
  constexpr int kBins = 2048;
  std::vector<double> count(kBins, 0.0);
  for (float s : sigma)
    if (s > 0) ++count[size_t(std::min(kBins - 1, int(double(s) / largest * kBins)))];
  std::vector<std::pair<double, double>> bins;  // (pixels, σ) of each occupied bin
  for (int b = 0; b < kBins; ++b)
    if (count[size_t(b)] > 0) bins.emplace_back(count[size_t(b)], largest * (b + 0.5) / kBins);
  const double n = double(sigma.size());
  double lo = 0, hi = 6.0 * largest, x = 0;
  for (int i = 0; i < 100; ++i) {
    double excess = -0.01, slope = 0;  // the share beyond x less 1 %, and its derivative
    for (const auto& [pixels, s] : bins) {
      const double z = x / (s * std::sqrt(2.0));
      excess += pixels / n * std::erfc(z);
      slope -= pixels / n * std::sqrt(2.0 / M_PI) / s * std::exp(-z * z);
    }
    (excess > 0 ? lo : hi) = x;
    double next = slope < 0 ? x - excess / slope : hi;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - x) <= 1e-12 * next) return next;
    x = next;
  }
  return x;
}

}  // namespace

double quantized_noise_steps(double r) {
  r = std::abs(r);
  if (!(r < kTableMax)) return std::sqrt(r * r + 1.0 / 12.0);  // NaN stays NaN, not an index
  static QuantizedTable table;
  const double x = r / kTableMax * kTableSteps;
  const int i = std::min(int(x), kTableSteps - 1);
  const double f = x - i;
  return std::sqrt((1.0 - f) * table[i] + f * table[i + 1]);
}

NoiseModel lambda_noise(const View& view, const ChangeNoise* change, double lambda,
                        const std::vector<float>& extra) {
  const std::vector<float>& own = view.render.noise;
  NoiseModel model;
  model.sigma.resize(own.size());
  for (size_t p = 0; p < own.size(); ++p) {
    double variance = double(own[p]) * own[p];
    if (change)
      variance += 2.0 * lambda * change->covariance[p] + lambda * lambda * change->variance[p];
    if (!extra.empty()) variance += lambda * lambda * double(extra[p]) * extra[p];
    // At an absurd λ the terms overflow, and inf − inf is NaN: the noise is unbounded then.
    if (std::isnan(variance)) variance = std::numeric_limits<double>::infinity();
    model.sigma[p] = float(std::sqrt(std::max(variance, 0.0)));
  }
  return model;
}

std::vector<float> stimulus_noise(const View& view, const NoiseModel& model, const Image& written) {
  const size_t n = size_t(written.width) * written.height;
  const std::vector<float>& before = model.sigma.empty() ? view.render.noise : model.sigma;
  std::vector<float> sigma(n, 0.0f);
  if (before.size() != n) return sigma;  // an external image: no estimate
  const CodeLightness codes(view.encoding, view.bits);
  StepCache step(codes);
  for (size_t p = 0; p < n; ++p) {
    const double s = before[p];
    const double q = step(&written.pixels[3 * p]);
    sigma[p] = float(q > 0 ? q * quantized_noise_steps(s / q) : s);
  }
  return sigma;
}

NoiseSummary summarize_noise(const std::vector<float>& sigma) {
  NoiseSummary out;
  if (sigma.empty()) return out;
  double sum = 0, largest = 0;
  for (float s : sigma) {
    sum += double(s) * s;
    largest = std::max(largest, double(s));
  }
  out.rms = std::sqrt(sum / double(sigma.size()));
  if (largest <= 0) return out;
  if (!std::isfinite(largest)) {  // some pixel's noise is unbounded (an absurd λ), and so is p99
    out.p99 = largest;
    return out;
  }
  out.p99 = ninety_ninth_percentile(sigma, largest);
  return out;
}

}  // namespace countershade
