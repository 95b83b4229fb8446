#include "enhance/depth_usm.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/error.h"
#include "core/gaussian.h"
#include "enhance/usm2d.h"

namespace countershade {
namespace {

bool valid_depth(float d) { return std::isfinite(d) && d > 0.0f; }

// Histogram-based global contrast: a 1st–99th percentile stretch or an equalisation, computed
// jointly over all values (all channels), so colour balance is kept.
class GlobalContrast {
 public:
  GlobalContrast(const std::vector<float>& values, double range, bool equalize) : range_(range), equalize_(equalize) {
    std::vector<double> histogram(kBins, 0.0);
    for (float v : values) histogram[bin(v)] += 1.0;
    cdf_.resize(kBins);
    double total = 0;
    for (size_t b = 0; b < kBins; ++b) cdf_[b] = total += histogram[b];
    for (double& c : cdf_) c /= std::max(total, 1.0);
    auto percentile = [&](double p) {
      size_t b = size_t(std::lower_bound(cdf_.begin(), cdf_.end(), p) - cdf_.begin());
      return (double(std::min(b, kBins - 1)) + 0.5) / double(kBins) * range_;
    };
    lo_ = percentile(0.01);
    hi_ = percentile(0.99);
  }
  double operator()(double v) const {
    if (equalize_) return cdf_[bin(float(v))] * range_;
    if (hi_ <= lo_) return v;
    return std::clamp((v - lo_) / (hi_ - lo_), 0.0, 1.0) * range_;
  }

 private:
  static constexpr size_t kBins = 4096;
  size_t bin(float v) const { return std::min(kBins - 1, size_t(std::max(0.0, double(v) / range_) * kBins)); }
  double range_;
  bool equalize_;
  std::vector<double> cdf_;
  double lo_ = 0, hi_ = 1;
};

enum class Operator { add, contrast, darken, color };

Operator parse_operator(const std::string& name) {
  if (name == "add") return Operator::add;
  if (name == "contrast") return Operator::contrast;
  if (name == "color") return Operator::color;
  return Operator::darken;
}

// Runs body(begin, end) over [0, n) in parallel chunks.
template <class Body>
void parallel_chunks(size_t n, const Body& body) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 8192),
                    [&](const tbb::blocked_range<size_t>& r) { body(r.begin(), r.end()); });
}

// out = clamp(in + a·min(ΔD, 0) + b·max(ΔD, 0)) for `n` RGB pixels; returns how many clipped.
// Runs in float over blocks (first the per-pixel offsets, then the channels) so that both loops
// vectorise; compiled for AVX2/FMA machines and for the x86-64 baseline, chosen at load time.
__attribute__((target_clones("arch=x86-64-v3", "default")))
unsigned offset_and_clip(const float* in, const float* dd, float* out, size_t n, const float c[6]) {
  constexpr size_t kBlock = 1024;
  float off0[kBlock], off1[kBlock], off2[kBlock];
  unsigned clipped = 0;
  for (size_t first = 0; first < n; first += kBlock) {
    const size_t m = std::min(kBlock, n - first);
    for (size_t k = 0; k < m; ++k) {
      const float d = dd[first + k], neg = std::min(d, 0.0f), pos = std::max(d, 0.0f);
      off0[k] = c[0] * neg + c[3] * pos;
      off1[k] = c[1] * neg + c[4] * pos;
      off2[k] = c[2] * neg + c[5] * pos;
    }
    const float* p = in + 3 * first;
    float* o = out + 3 * first;
    for (size_t k = 0; k < m; ++k) {
      const float v0 = p[3 * k] + off0[k], v1 = p[3 * k + 1] + off1[k], v2 = p[3 * k + 2] + off2[k];
      const float lo = std::min(v0, std::min(v1, v2)), hi = std::max(v0, std::max(v1, v2));
      clipped += unsigned(lo < 0.0f) | unsigned(hi > 1.0f);
      o[3 * k] = std::min(std::max(v0, 0.0f), 1.0f);
      o[3 * k + 1] = std::min(std::max(v1, 0.0f), 1.0f);
      o[3 * k + 2] = std::min(std::max(v2, 0.0f), 1.0f);
    }
  }
  return clipped;
}

// The range of the valid depths (finite and positive) among n values; lo > hi when none is valid.
__attribute__((target_clones("arch=x86-64-v3", "default")))
void valid_depth_range(const float* depth, size_t n, float* lo, float* hi) {
  float l = INFINITY, h = -INFINITY;
  for (size_t i = 0; i < n; ++i) {
    const float d = depth[i];
    const bool valid = d > 0.0f && d < INFINITY;  // NaN fails both
    l = std::min(l, valid ? d : INFINITY);
    h = std::max(h, valid ? d : -INFINITY);
  }
  *lo = l;
  *hi = h;
}

// Linear depth mapped to [0,1] as (d − lo)·scale; invalid depths become 1 (far).
__attribute__((target_clones("arch=x86-64-v3", "default")))
void normalize_linear_depth(const float* depth, float* out, size_t n, double lo, double scale) {
  for (size_t i = 0; i < n; ++i) {
    const float d = depth[i];
    const bool valid = d > 0.0f && d < INFINITY;
    out[i] = valid ? float((double(d) - lo) * scale) : 1.0f;
  }
}

class DepthUsmPrepared final : public PreparedEnhancement {
 public:
  DepthUsmPrepared(const View& view, const MethodOptions& options, SpatialImportance importance)
      : view_(view), options_(options), op_(parse_operator(options.op)), si_(std::move(importance)) {
    const size_t n = view.lab.size();
    if (op_ != Operator::contrast) return;
    // The contrast-enhanced version C(I), once per view and kernel.
    const bool lab = options.space == "lab";
    std::vector<float> values(lab ? n : 3 * n);
    for (size_t i = 0; i < n; ++i) {
      if (lab) values[i] = float(view.lab[i].L);
      else for (int c = 0; c < 3; ++c) values[3 * i + c] = view.display.pixels[3 * i + c];
    }
    const double range = lab ? 100.0 : 1.0;
    enhanced_.resize(values.size());
    if (options.contrast == "local") {
      // Local contrast enhancement (an unsharp mask with the same kernel): flat, untextured
      // regions stay as they are, which hides artefacts of noisy depth.
      int channels = lab ? 1 : 3;
      std::vector<float> plane(n), blurred(n);
      for (int c = 0; c < channels; ++c) {
        for (size_t i = 0; i < n; ++i) plane[i] = values[size_t(channels) * i + c];
        gaussian_blur(plane.data(), blurred.data(), view.width(), view.height(), si_.sigma_px);
        for (size_t i = 0; i < n; ++i)
          enhanced_[size_t(channels) * i + c] = float(std::clamp(2.0 * plane[i] - blurred[i], 0.0, range));
      }
    } else {
      GlobalContrast contrast(values, range, options.contrast == "equalize");
      for (size_t i = 0; i < values.size(); ++i) enhanced_[i] = float(contrast(values[i]));
    }
  }

  Composed compose(double lambda) const override {
    const size_t n = view_.lab.size();
    const float* dd = si_.importance.pixels.data();
    if (options_.space == "lab") {
      std::vector<double> delta(n);
      const glm::dvec3 y(0.2126, 0.7152, 0.0722);
      const double cold = glm::dot(y, options_.cold), warm = glm::dot(y, options_.warm);
      parallel_chunks(n, [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) {
          double d = dd[i], neg = std::min(d, 0.0), pos = std::max(d, 0.0);
          switch (op_) {
            case Operator::add: delta[i] = 100.0 * lambda * d; break;
            case Operator::darken: delta[i] = 100.0 * lambda * neg; break;
            case Operator::color: delta[i] = 100.0 * lambda * (-neg * cold + pos * warm); break;
            case Operator::contrast:
              delta[i] = std::clamp(lambda * std::abs(d), 0.0, 1.0) * (double(enhanced_[i]) - view_.lab[i].L);
          }
        }
      });
      return compose_lightness(view_.display, view_.lab, delta, view_.encoding);
    }
    Composed out;
    out.display = Image(view_.width(), view_.height(), 3, Image::Uninitialized{});  // every pixel is written below
    std::atomic<size_t> clipped{0};
    switch (op_) {
      // add, darken and color are all I + λ(a·min(ΔD, 0) + b·max(ΔD, 0)) per channel.
      case Operator::add: clipped = apply_linear(out.display, lambda * glm::dvec3(1.0), lambda * glm::dvec3(1.0)); break;
      case Operator::darken: clipped = apply_linear(out.display, lambda * glm::dvec3(1.0), glm::dvec3(0.0)); break;
      case Operator::color: clipped = apply_linear(out.display, -lambda * options_.cold, lambda * options_.warm); break;
      case Operator::contrast:
        clipped = apply_rgb(out.display, [&](size_t i, int c, double I, double d) {
          double alpha = std::clamp(lambda * std::abs(d), 0.0, 1.0);
          return double(enhanced_[3 * i + c]) * alpha + I * (1.0 - alpha);
        });
    }
    out.clipped_pixels = clipped;
    return out;
  }

  // Writes I + a·min(ΔD, 0) + b·max(ΔD, 0), clipped to [0,1], into `result`; returns the clipped
  // pixel count. This loop is most of the cost of a further λ.
  size_t apply_linear(Image& result, const glm::dvec3& a, const glm::dvec3& b) const {
    std::atomic<size_t> clipped{0};
    const float* in = view_.display.pixels.data();
    const float* dd = si_.importance.pixels.data();
    float* out = result.pixels.data();
    const float coefficients[6] = {float(a.x), float(a.y), float(a.z), float(b.x), float(b.y), float(b.z)};
    parallel_chunks(view_.lab.size(), [&](size_t begin, size_t end) {
      clipped += offset_and_clip(in + 3 * begin, dd + begin, out + 3 * begin, end - begin, coefficients);
    });
    return clipped;
  }

  // Writes op(pixel, channel, I, ΔD) clipped to [0,1] into `result`; returns the clipped pixel count.
  template <class Op>
  size_t apply_rgb(Image& result, const Op& op) const {
    std::atomic<size_t> clipped{0};
    const float* in = view_.display.pixels.data();
    const float* dd = si_.importance.pixels.data();
    float* out = result.pixels.data();
    parallel_chunks(view_.lab.size(), [&](size_t begin, size_t end) {
      size_t local = 0;
      for (size_t i = begin; i < end; ++i) {
        double d = dd[i];
        double v0 = op(i, 0, in[3 * i], d), v1 = op(i, 1, in[3 * i + 1], d), v2 = op(i, 2, in[3 * i + 2], d);
        local += (v0 < 0.0) | (v0 > 1.0) | (v1 < 0.0) | (v1 > 1.0) | (v2 < 0.0) | (v2 > 1.0);
        out[3 * i] = float(std::clamp(v0, 0.0, 1.0));
        out[3 * i + 1] = float(std::clamp(v1, 0.0, 1.0));
        out[3 * i + 2] = float(std::clamp(v2, 0.0, 1.0));
      }
      clipped += local;
    });
    return clipped;
  }

  nlohmann::json parameters() const override {
    return {{"operator", options_.op}, {"sigma_px", si_.sigma_px}, {"space", options_.space},
            {"depth_mapping", options_.depth_mapping}, {"contrast", options_.contrast}};
  }
  std::vector<std::pair<std::string, Image>> auxiliary() const override {
    return {{"depth_normalized", si_.depth}, {"depth_blurred", si_.blurred}, {"spatial_importance", si_.importance}};
  }

 private:
  const View& view_;
  MethodOptions options_;
  Operator op_;
  SpatialImportance si_;
  std::vector<float> enhanced_;  // C(I): RGB or L*, for the contrast operator
};

}  // namespace

SpatialImportance spatial_importance(const View& view, const MethodOptions& options) {
  const int w = view.width(), h = view.height();
  const size_t n = size_t(w) * h;
  if (view.depth.size() != n) throw InputError("depth-usm: the view has no depth map of the image's size");
  float lo = INFINITY, hi = -INFINITY;
  std::mutex range_mutex;
  parallel_chunks(n, [&](size_t begin, size_t end) {
    float l, h;
    valid_depth_range(view.depth.data() + begin, end - begin, &l, &h);
    std::lock_guard<std::mutex> lock(range_mutex);
    lo = std::min(lo, l);
    hi = std::max(hi, h);
  });
  SpatialImportance si;
  const bool linear_fills_all = options.depth_mapping != "zbuffer" && lo <= hi;
  si.depth = linear_fills_all ? Image(w, h, 1, Image::Uninitialized{}) : Image(w, h, 1, 1.0f);
  const bool zbuffer = options.depth_mapping == "zbuffer";
  double near = options.z_near.value_or(lo), far = options.z_far.value_or(hi);
  auto mapped = [&](double d) {  // a monotone depth value before normalisation
    if (!zbuffer) return d;
    return (1.0 / near - 1.0 / d) / (1.0 / near - 1.0 / far);  // the [0,1] z-buffer of a perspective camera
  };
  if (lo <= hi) {
    double mlo = mapped(lo), mhi = mapped(hi);
    if (!zbuffer) {
      const double scale = hi > lo ? 1.0 / (double(hi) - double(lo)) : 0.0;
      parallel_chunks(n, [&](size_t begin, size_t end) {
        normalize_linear_depth(view.depth.data() + begin, si.depth.pixels.data() + begin, end - begin, lo, scale);
      });
    } else {
      parallel_chunks(n, [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) {
          float d = view.depth[i];
          if (!valid_depth(d)) continue;  // background stays at 1 (far)
          si.depth.pixels[i] = mhi > mlo ? float((mapped(d) - mlo) / (mhi - mlo)) : 0.0f;
        }
      });
    }
  }
  si.sigma_px = image_sigma_px(options, w, h);
  si.blurred = Image(w, h, 1, Image::Uninitialized{});  // the blur writes every pixel
  gaussian_blur(si.depth.pixels.data(), si.blurred.pixels.data(), w, h, si.sigma_px);
  si.importance = Image(w, h, 1, Image::Uninitialized{});
  parallel_chunks(n, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) si.importance.pixels[i] = si.blurred.pixels[i] - si.depth.pixels[i];
  });
  return si;
}

void DepthUsmMethod::validate(const MethodOptions& o) const {
  validate_image_width("depth-usm", o);
  auto one_of = [](const std::string& v, std::initializer_list<const char*> choices) {
    for (const char* c : choices)
      if (v == c) return true;
    return false;
  };
  if (!one_of(o.op, {"add", "contrast", "darken", "color"}))
    throw InputError("--operator: unknown operator '" + o.op + "' (expected add, contrast, darken or color)");
  if (!one_of(o.contrast, {"stretch", "equalize", "local"}))
    throw InputError("--contrast: unknown mode '" + o.contrast + "' (expected stretch, equalize or local)");
  if (!one_of(o.space, {"rgb", "lab"})) throw InputError("--space: expected rgb or lab");
  if (!one_of(o.depth_mapping, {"linear", "zbuffer"})) throw InputError("--depth-mapping: expected linear or zbuffer");
  if ((o.z_near && !(*o.z_near > 0)) || (o.z_far && o.z_near && !(*o.z_far > *o.z_near)))
    throw InputError("--z-near/--z-far: need 0 < near < far");
}

std::unique_ptr<PreparedEnhancement> DepthUsmMethod::prepare(const View& view, const MethodOptions& options) const {
  validate(options);
  return std::make_unique<DepthUsmPrepared>(view, options, spatial_importance(view, options));
}

}  // namespace countershade
