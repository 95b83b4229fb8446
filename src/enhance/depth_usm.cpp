#include "enhance/depth_usm.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cfloat>
#include <cmath>
#include <mutex>

#include "core/error.h"
#include "core/gaussian.h"
#include "core/parallel.h"
#include "enhance/depth_coverage.h"
#include "enhance/image_width.h"
#include "enhance/lightness.h"
#include "enhance/stimulus_noise.h"

namespace countershade {

GlobalContrast::GlobalContrast(const std::vector<float>& values, double range, bool equalize)
    : range_(range), equalize_(equalize) {
  std::vector<double> histogram(kBins, 0.0);
  for (float v : values) histogram[bin(v)] += 1.0;
  cdf_.resize(kBins);
  double total = 0;
  for (size_t b = 0; b < kBins; ++b) cdf_[b] = total += histogram[b];
  for (double& c : cdf_) c /= std::max(total, 1.0);
  // The CDF at the lowest occupied bin: equalisation maps that bin to 0, so a large dark
  // background stays dark instead of being lifted by its own share of the pixels.
  for (size_t b = 0; b < kBins; ++b)
    if (histogram[b] > 0) {
      cdf_min_ = cdf_[b];
      break;
    }
  auto percentile = [&](double p) {
    size_t b = size_t(std::lower_bound(cdf_.begin(), cdf_.end(), p) - cdf_.begin());
    return (double(std::min(b, kBins - 1)) + 0.5) / double(kBins) * range_;
  };
  lo_ = percentile(0.01);
  hi_ = percentile(0.99);
}

size_t GlobalContrast::bin(float v) const {
  return std::min(kBins - 1, size_t(std::max(0.0, double(v) / range_) * kBins));
}

double GlobalContrast::operator()(double v) const {
  if (equalize_)
    return cdf_min_ < 1.0 ? (cdf_[bin(float(v))] - cdf_min_) / (1.0 - cdf_min_) * range_ : v;
  if (hi_ <= lo_) return v;
  return std::clamp((v - lo_) / (hi_ - lo_), 0.0, 1.0) * range_;
}

namespace {

enum class Operator { add, contrast, darken, color };
enum class ContrastKind { stretch, equalize, local };

struct DepthUsmParameters final : MethodParameters {
  ImageWidth width;
  Operator op = Operator::darken;
  std::string op_name = "darken";
  ContrastKind contrast = ContrastKind::stretch;
  std::string contrast_name = "stretch";
  bool lab = false;
  DepthMapping mapping;
  glm::dvec3 cold{-0.1, -0.05, 0.15}, warm{0.15, 0.1, -0.1};
};

// Runs body(begin, end) over [0, n) in parallel chunks.
template <class Body>
void parallel_chunks(size_t n, const Body& body) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 8192),
                    [&](const tbb::blocked_range<size_t>& r) { body(r.begin(), r.end()); });
}

// out = clamp(in + a·min(ΔD, 0) + b·max(ΔD, 0)) for `n` RGB pixels, the two terms given per pixel;
// returns how many clipped.
// Runs in float over blocks (first the per-pixel offsets, then the channels) so that both loops
// vectorise; compiled for AVX2/FMA machines and for the x86-64 baseline, chosen at load time.
__attribute__((target_clones("arch=x86-64-v3", "default"))) unsigned offset_and_clip(
    const float* in, const float* darker, const float* lighter, float* out, size_t n,
    const float c[6]) {
  constexpr size_t kBlock = 1024;
  float off0[kBlock], off1[kBlock], off2[kBlock];
  unsigned clipped = 0;
  for (size_t first = 0; first < n; first += kBlock) {
    const size_t m = std::min(kBlock, n - first);
    for (size_t k = 0; k < m; ++k) {
      const float neg = darker[first + k], pos = lighter[first + k];
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
__attribute__((target_clones("arch=x86-64-v3", "default"))) void valid_depth_range(
    const float* depth, size_t n, float* lo, float* hi) {
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
__attribute__((target_clones("arch=x86-64-v3", "default"))) void normalize_linear_depth(
    const float* depth, float* out, size_t n, double lo, double scale) {
  for (size_t i = 0; i < n; ++i) {
    const float d = depth[i];
    const bool valid = d > 0.0f && d < INFINITY;
    out[i] = valid ? float((double(d) - lo) * scale) : 1.0f;
  }
}

// C(I) for the contrast operator, once per view and kernel: RGB (3 values per pixel) or L*.
std::vector<float> contrast_enhanced(const View& view, const DepthUsmParameters& p, double sigma_px,
                                     int threads) {
  const size_t n = view.lab.size();
  const int channels = p.lab ? 1 : 3;
  std::vector<float> values(size_t(channels) * n);
  for (size_t i = 0; i < n; ++i) {
    if (p.lab)
      values[i] = float(view.lab[i].L);
    else
      for (int c = 0; c < 3; ++c) values[3 * i + c] = view.display.pixels[3 * i + c];
  }
  const double range = p.lab ? 100.0 : 1.0;
  std::vector<float> enhanced(values.size());
  if (p.contrast == ContrastKind::local) {
    // Local contrast enhancement (an unsharp mask with the same kernel): flat, untextured
    // regions stay as they are, which hides artefacts of noisy depth.
    std::vector<float> plane(n), blurred(n);
    for (int c = 0; c < channels; ++c) {
      for (size_t i = 0; i < n; ++i) plane[i] = values[size_t(channels) * i + c];
      gaussian_blur(plane.data(), blurred.data(), view.width(), view.height(), sigma_px, threads);
      for (size_t i = 0; i < n; ++i)
        enhanced[size_t(channels) * i + c] =
            float(std::clamp(2.0 * plane[i] - blurred[i], 0.0, range));
    }
  } else {
    GlobalContrast contrast(values, range, p.contrast == ContrastKind::equalize);
    for (size_t i = 0; i < values.size(); ++i) enhanced[i] = float(contrast(values[i]));
  }
  return enhanced;
}

// The paper's operators on display RGB.
// The importance layer as depth-usm's mask: 100·ΔD, so that its flicker reads on the scale of L*.
std::vector<float> importance_mask(const SpatialImportance& si) {
  std::vector<float> m(si.importance.pixels.size());
  for (size_t i = 0; i < m.size(); ++i) m[i] = 100.0f * si.importance.pixels[i];
  return m;
}

class DepthUsmRgb final : public PreparedEnhancement {
 public:
  DepthUsmRgb(std::shared_ptr<const View> view, const DepthUsmParameters& p, SpatialImportance si,
              nlohmann::json record, std::vector<float> enhanced, const ChangeNoise* change_noise)
      : view_(std::move(view)),
        p_(p),
        si_(std::move(si)),
        record_(std::move(record)),
        enhanced_(std::move(enhanced)),
        change_noise_(change_noise) {}

  Composed compose(double lambda) const override {
    Composed out;
    out.display = Image(view_->width(), view_->height(), 3,
                        Image::Uninitialized{});  // every pixel is written below
    switch (p_.op) {
      // add, darken and color are all I + λ(a·min(ΔD, 0) + b·max(ΔD, 0)) per channel.
      case Operator::add:
        out.clipped_pixels =
            apply_linear(out.display, lambda * glm::dvec3(1.0), lambda * glm::dvec3(1.0));
        break;
      case Operator::darken:
        out.clipped_pixels = apply_linear(out.display, lambda * glm::dvec3(1.0), glm::dvec3(0.0));
        break;
      case Operator::color:
        out.clipped_pixels = apply_linear(out.display, -lambda * p_.cold, lambda * p_.warm);
        break;
      case Operator::contrast:
        out.clipped_pixels = apply_contrast(out.display, lambda);
        break;
    }
    return out;
  }
  nlohmann::json parameters() const override { return record_; }
  std::vector<std::pair<std::string, Image>> auxiliary() const override {
    return {{"depth_normalized", si_.depth},
            {"depth_blurred", si_.blurred},
            {"spatial_importance", si_.importance}};
  }
  NoiseModel noise(double lambda) const override {
    return lambda_noise(*view_, change_noise_, lambda);
  }
  std::vector<float> mask() const override { return importance_mask(si_); }

 private:
  // Writes I + a·min(ΔD, 0) + b·max(ΔD, 0), clipped to [0,1], into `result`; returns the clipped
  // pixel count. This loop is most of the cost of a further λ.
  size_t apply_linear(Image& result, const glm::dvec3& a, const glm::dvec3& b) const {
    std::atomic<size_t> clipped{0};
    const float* in = view_->display.pixels.data();
    const float *darker = si_.darker.pixels.data(), *lighter = si_.lighter.pixels.data();
    float* out = result.pixels.data();
    // Beyond float's range a coefficient would be inf, and inf × a zero ΔD is NaN. |ΔD| ≤ 1, so
    // at ±FLT_MAX each term stays finite or saturates, and the clip does the rest.
    const auto coefficient = [](double c) {
      return float(std::clamp(c, -double(FLT_MAX), double(FLT_MAX)));
    };
    const float coefficients[6] = {coefficient(a.x), coefficient(a.y), coefficient(a.z),
                                   coefficient(b.x), coefficient(b.y), coefficient(b.z)};
    parallel_chunks(view_->lab.size(), [&](size_t begin, size_t end) {
      clipped += offset_and_clip(in + 3 * begin, darker + begin, lighter + begin, out + 3 * begin,
                                 end - begin, coefficients);
    });
    return clipped;
  }

  // C(I)·α + I·(1−α), α = clamp(λ|ΔD|, 0, 1), clipped to [0,1]; returns the clipped pixel count.
  // |ΔD| is max(ΔD, 0) − min(ΔD, 0), so at depth edges its mean over the pixel's area.
  size_t apply_contrast(Image& result, double lambda) const {
    std::atomic<size_t> clipped{0};
    const float* in = view_->display.pixels.data();
    const float *darker = si_.darker.pixels.data(), *lighter = si_.lighter.pixels.data();
    float* out = result.pixels.data();
    parallel_chunks(view_->lab.size(), [&](size_t begin, size_t end) {
      size_t local = 0;
      for (size_t i = begin; i < end; ++i) {
        const double alpha = std::clamp(lambda * double(lighter[i] - darker[i]), 0.0, 1.0);
        bool clip = false;
        for (int c = 0; c < 3; ++c) {
          const double v =
              double(enhanced_[3 * i + c]) * alpha + double(in[3 * i + c]) * (1.0 - alpha);
          clip |= v < 0.0 || v > 1.0;
          out[3 * i + c] = float(std::clamp(v, 0.0, 1.0));
        }
        local += clip;
      }
      clipped += local;
    });
    return clipped;
  }

  std::shared_ptr<const View> view_;
  DepthUsmParameters p_;
  SpatialImportance si_;
  nlohmann::json record_;
  std::vector<float> enhanced_;
  const ChangeNoise* change_noise_;  // C(I), for the contrast operator
};

// The same scalar term as a lightness-only change (space lab).
LightnessChange lab_change(const View& view, const DepthUsmParameters& p,
                           const SpatialImportance& si, const std::vector<float>& enhanced) {
  const size_t n = view.lab.size();
  const float *darker = si.darker.pixels.data(), *lighter = si.lighter.pixels.data();
  LightnessChange change;
  change.amount.resize(n);
  if (p.op == Operator::contrast) {
    change.kind = LightnessChange::Kind::blended;
    change.weight.resize(n);
    for (size_t i = 0; i < n; ++i) {
      change.weight[i] = lighter[i] - darker[i];  // |ΔD|
      change.amount[i] = double(enhanced[i]) - view.lab[i].L;
    }
    return change;
  }
  change.factor = 100.0;  // ΔD is in [−1, 1]; L* spans 100
  // add: ΔD = min(ΔD, 0) + max(ΔD, 0); darken: min(ΔD, 0).
  for (size_t i = 0; i < n; ++i)
    change.amount[i] = p.op == Operator::add ? double(darker[i] + lighter[i]) : double(darker[i]);
  return change;
}

Operator parse_operator(const std::string& name) {
  if (name == "add") return Operator::add;
  if (name == "contrast") return Operator::contrast;
  if (name == "color") return Operator::color;
  return Operator::darken;
}

// `depth_range` NEAR,FAR: two eye depths with 0 ≤ NEAR < FAR, or none.
std::optional<std::pair<double, double>> read_depth_range(const ParameterBag& bag) {
  if (!bag.has("depth_range")) return std::nullopt;
  const std::vector<double> r = bag.numbers("depth_range", {});
  if (r.size() != 2 || !(r[0] >= 0) || !(r[1] > r[0]))
    bag.fail("depth_range", "expected NEAR,FAR with 0 <= NEAR < FAR");
  return std::make_pair(r[0], r[1]);
}

class DepthUsmMethod final : public EnhancementMethod {
 public:
  std::string name() const override { return "depth-usm"; }
  std::string summary() const override { return "depth-buffer unsharp masking (Luft et al. 2006)"; }
  MethodAxes axes() const override {
    return {"strength λ of the operator on ΔD = G*D − D", image_width_axes()};
  }
  std::vector<ParameterDoc> parameter_docs() const override {
    std::vector<ParameterDoc> docs = image_width_docs();
    docs.insert(
        docs.end(),
        {{"operator", "darken", "add | contrast | darken | color (Luft et al. 2006, eqs. 2–5)"},
         {"contrast", "stretch", "C for the contrast operator: stretch | equalize | local"},
         {"space", "rgb", "rgb (display RGB, as published) | lab (the same term on L* only)"},
         {"depth_mapping", "linear", "linear eye depth | zbuffer (non-linear, near/far)"},
         {"z_near", "", "zbuffer near plane (default: the nearest depth)"},
         {"z_far", "", "zbuffer far plane (default: the farthest depth)"},
         {"depth_range", "",
          "NEAR,FAR: eye depths D maps to 0 and 1, clamped (default: each image's own range; fix "
          "it for sequences)"},
         {"cold", "-0.1,-0.05,0.15", "color: the cold colour R,G,B"},
         {"warm", "0.15,0.1,-0.1", "color: the warm colour R,G,B"}});
    return docs;
  }

  std::shared_ptr<const MethodParameters> parse(const ParameterBag& bag) const override {
    auto p = std::make_shared<DepthUsmParameters>();
    p->width = read_image_width(bag);
    p->op_name = bag.choice("operator", "darken", {"add", "contrast", "darken", "color"});
    p->op = parse_operator(p->op_name);
    p->lab = bag.choice("space", "rgb", {"rgb", "lab"}) == "lab";
    if (p->op == Operator::color) {
      if (p->lab)
        bag.fail("space",
                 "the color operator shifts hue (Luft et al. 2006, eq. 5) and lab changes "
                 "lightness only; "
                 "use rgb, or another operator");
      p->cold = bag.vec3("cold", p->cold);
      p->warm = bag.vec3("warm", p->warm);
    }
    if (p->op == Operator::contrast) {
      p->contrast_name = bag.choice("contrast", "stretch", {"stretch", "equalize", "local"});
      p->contrast = p->contrast_name == "equalize" ? ContrastKind::equalize
                    : p->contrast_name == "local"  ? ContrastKind::local
                                                   : ContrastKind::stretch;
    }
    p->mapping.zbuffer = bag.choice("depth_mapping", "linear", {"linear", "zbuffer"}) == "zbuffer";
    if (p->mapping.zbuffer) {
      p->mapping.z_near = bag.optional_number("z_near");
      p->mapping.z_far = bag.optional_number("z_far");
    }
    p->mapping.range = read_depth_range(bag);
    bag.finish(name());
    check_image_width(p->width, bag, name());
    if (p->mapping.z_near && !(*p->mapping.z_near > 0)) bag.fail("z_near", "need 0 < near < far");
    if (p->mapping.z_far && p->mapping.z_near && !(*p->mapping.z_far > *p->mapping.z_near))
      bag.fail("z_far", "need 0 < near < far");
    return p;
  }

  RenderRequest request(const MethodParameters&) const override {
    RenderRequest r;
    r.depth = true;
    return r;
  }
  // The contrast operator blends towards a contrast-stretched image, which carries a pixel's own
  // noise (modelled as c = L); the other operators add a change that depends on depth only.
  std::shared_ptr<const ChangePerLambda> change_per_lambda(
      const MethodParameters& parameters) const override {
    if (parameters_as<DepthUsmParameters>(parameters).op != Operator::contrast) return nullptr;
    return std::make_shared<LightnessTimes>(1.0);
  }
  std::string label(const MethodParameters& parameters) const override {
    const auto& p = parameters_as<DepthUsmParameters>(parameters);
    return name() + "-" + p.op_name + (p.lab ? "-lab" : "");
  }

  std::unique_ptr<PreparedEnhancement> prepare(const PrepareContext& context,
                                               const MethodParameters& parameters) const override {
    const auto& p = parameters_as<DepthUsmParameters>(parameters);
    const View& view = *context.view;
    const double sigma = p.width.sigma_px_for(view.width(), view.height());
    SpatialImportance si = spatial_importance(view, p.mapping, sigma, context.threads);
    std::vector<float> enhanced;
    if (p.op == Operator::contrast) enhanced = contrast_enhanced(view, p, sigma, context.threads);
    nlohmann::json record = {{"operator", p.op_name},
                             {"sigma_px", sigma},
                             {"space", p.lab ? "lab" : "rgb"},
                             {"depth_mapping", p.mapping.zbuffer ? "zbuffer" : "linear"},
                             {"contrast", p.contrast_name}};
    if (p.mapping.range) record["depth_range"] = {p.mapping.range->first, p.mapping.range->second};
    if (!p.lab)
      return std::make_unique<DepthUsmRgb>(context.view, p, std::move(si), std::move(record),
                                           std::move(enhanced), context.change_noise);
    LightnessChange change = lab_change(view, p, si, enhanced);
    std::vector<std::pair<std::string, Image>> aux = {{"depth_normalized", si.depth},
                                                      {"depth_blurred", si.blurred},
                                                      {"spatial_importance", si.importance}};
    auto prepared =
        std::make_unique<LightnessPrepared>(context.view, std::move(change), std::move(record),
                                            std::move(aux), context.threads, plain_noise(context));
    prepared->set_mask([importance = importance_mask(si)] { return importance; });
    return prepared;
  }
};

// How one linear eye depth becomes D in [0,1]: the view's valid range, mapped linearly or as a
// perspective z-buffer; invalid depths (background) are 1 (far).
struct DepthNormaliser {
  bool any = false, zbuffer = false;  // any: some depth is valid
  double lo = 0, scale = 0;           // linear: (d − lo)·scale
  double near = 1, far = 2, mlo = 0, mhi = 0;
  double mapped(double d) const { return (1.0 / near - 1.0 / d) / (1.0 / near - 1.0 / far); }
  bool clamp = false;  // a fixed range: depths outside it map to 0 or 1
  float operator()(float d) const {
    if (!any || !valid_eye_depth(d)) return 1.0f;
    const double D = !zbuffer    ? (double(d) - lo) * scale
                     : mhi > mlo ? (mapped(d) - mlo) / (mhi - mlo)
                                 : 0.0;
    return float(clamp ? std::clamp(D, 0.0, 1.0) : D);
  }
};

// The range of the view's valid depths; lo > hi when none is valid.
std::pair<float, float> view_depth_range(const View& view) {
  float lo = INFINITY, hi = -INFINITY;
  std::mutex range_mutex;
  parallel_chunks(view.depth.size(), [&](size_t begin, size_t end) {
    float l, hh;
    valid_depth_range(view.depth.data() + begin, end - begin, &l, &hh);
    std::lock_guard<std::mutex> lock(range_mutex);
    lo = std::min(lo, l);
    hi = std::max(hi, hh);
  });
  return {lo, hi};
}

DepthNormaliser depth_normaliser(const View& view, const DepthMapping& mapping) {
  // A fixed range needs no scan: an invalid depth maps to far whatever the range.
  auto [lo, hi] = mapping.range ? std::pair<float, float>(float(mapping.range->first),
                                                          float(mapping.range->second))
                                : view_depth_range(view);
  DepthNormaliser n;
  n.any = lo <= hi;
  n.zbuffer = mapping.zbuffer;
  n.clamp = mapping.range.has_value();
  if (!n.any) return n;
  n.lo = lo;
  n.scale = hi > lo ? 1.0 / (double(hi) - double(lo)) : 0.0;
  n.near = mapping.z_near.value_or(lo);
  n.far = mapping.z_far.value_or(hi);
  n.mlo = n.mapped(lo);
  n.mhi = n.mapped(hi);
  return n;
}

// D of every pixel, background and invalid pixels 1 (far).
Image normalized_depth(const View& view, const DepthNormaliser& normalise) {
  const int w = view.width(), h = view.height();
  const size_t n = size_t(w) * h;
  Image depth(w, h, 1, Image::Uninitialized{});  // every pixel is written below
  parallel_chunks(n, [&](size_t begin, size_t end) {
    if (normalise.any && !normalise.zbuffer &&
        !normalise.clamp)  // the common case, in a loop that vectorises
      normalize_linear_depth(view.depth.data() + begin, depth.pixels.data() + begin, end - begin,
                             normalise.lo, normalise.scale);
    else
      for (size_t i = begin; i < end; ++i) depth.pixels[i] = normalise(view.depth[i]);
  });
  return depth;
}

}  // namespace

SpatialImportance spatial_importance(const View& view, const DepthMapping& mapping, double sigma_px,
                                     int threads) {
  const int w = view.width(), h = view.height();
  const size_t n = size_t(w) * h;
  if (view.depth.size() != n)
    throw InputError("depth-usm: the view has no depth map of the image's size");
  SpatialImportance si;
  const DepthNormaliser normalise = depth_normaliser(view, mapping);
  si.depth = normalized_depth(view, normalise);
  si.sigma_px = sigma_px;
  si.blurred = Image(w, h, 1, Image::Uninitialized{});  // the blur writes every pixel
  gaussian_blur(si.depth.pixels.data(), si.blurred.pixels.data(), w, h, sigma_px, threads);
  si.importance = Image(w, h, 1, Image::Uninitialized{});
  si.darker = Image(w, h, 1, Image::Uninitialized{});
  si.lighter = Image(w, h, 1, Image::Uninitialized{});
  parallel_chunks(n, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const float dd = si.blurred.pixels[i] - si.depth.pixels[i];
      si.importance.pixels[i] = dd;
      si.darker.pixels[i] = std::min(dd, 0.0f);
      si.lighter.pixels[i] = std::max(dd, 0.0f);
    }
  });
  sample_outlines(view, si.blurred, normalise, si.darker, si.lighter, threads);
  return si;
}

std::unique_ptr<const EnhancementMethod> make_depth_usm_method() {
  return std::make_unique<DepthUsmMethod>();
}

}  // namespace countershade
