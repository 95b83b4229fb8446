#include "observer/detection_model.h"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
#include <stdexcept>

#include "observer/contrast_sensitivity.h"

namespace countershade::observer {
namespace {

struct FftwFree {
  void operator()(void* p) const { fftw_free(p); }
};

// FFTW's planner is not thread-safe; its transforms are.
std::mutex& planner_mutex() {
  static std::mutex mutex;
  return mutex;
}

// The filter's gain at horizontal and vertical frequency indices (kx, ky) of a W × H transform.
double filter_gain(int kx, int ky, int width, int height, double ppd, bool oblique) {
  const double fx = double(kx) * ppd / double(width);
  const double fy = double(ky <= height / 2 ? ky : ky - height) * ppd / double(height);
  const double f = std::hypot(fx, fy);
  double gain = sso_sensitivity(f);
  if (oblique) gain *= oblique_gain(f, std::atan2(fy, fx));
  return gain;
}

// A thread's transform arrays, grown to the largest image it has filtered (fftw_alloc's
// alignment, which the plans' new-array execution needs).
struct Scratch {
  std::unique_ptr<double, FftwFree> real;
  std::unique_ptr<fftw_complex, FftwFree> spectrum;
  size_t reals = 0, complexes = 0;
  void reserve(size_t n_real, size_t n_complex) {
    if (n_real > reals) real.reset(fftw_alloc_real(reals = n_real));
    if (n_complex > complexes) spectrum.reset(fftw_alloc_complex(complexes = n_complex));
  }
};

}  // namespace

struct CsfFilter::Plans {
  fftw_plan forward = nullptr, backward = nullptr;
  ~Plans() {
    const std::lock_guard<std::mutex> lock(planner_mutex());
    if (forward) fftw_destroy_plan(forward);
    if (backward) fftw_destroy_plan(backward);
  }
};

CsfFilter::CsfFilter(int width, int height, double ppd, bool oblique)
    : width_(width), height_(height), ppd_(ppd), plans_(std::make_unique<Plans>()) {
  const int w = 2 * width, h = 2 * height, half = w / 2 + 1;
  const double normalise = 1.0 / (double(w) * double(h));  // FFTW's transforms are unscaled
  gains_.resize(size_t(half) * size_t(h));
  for (int ky = 0; ky < h; ++ky)
    for (int kx = 0; kx < half; ++kx)
      gains_[size_t(ky) * size_t(half) + size_t(kx)] =
          filter_gain(kx, ky, w, h, ppd, oblique) * normalise;
  // Planned on scratch arrays and run on others through FFTW's new-array interface, which
  // fftw_alloc's alignment allows.
  std::unique_ptr<double, FftwFree> real(fftw_alloc_real(size_t(w) * size_t(h)));
  std::unique_ptr<fftw_complex, FftwFree> spectrum(fftw_alloc_complex(gains_.size()));
  const std::lock_guard<std::mutex> lock(planner_mutex());
  plans_->forward = fftw_plan_dft_r2c_2d(h, w, real.get(), spectrum.get(), FFTW_ESTIMATE);
  plans_->backward = fftw_plan_dft_c2r_2d(h, w, spectrum.get(), real.get(), FFTW_ESTIMATE);
}

CsfFilter::~CsfFilter() = default;

ContrastImage CsfFilter::apply(const ContrastImage& contrast) const {
  if (contrast.width != width_ || contrast.height != height_)
    throw std::invalid_argument("CsfFilter: an image of another size");
  const int w = 2 * width_, h = 2 * height_;
  // Each thread keeps its transform arrays between images: a new 50 MB pair per image of a set
  // cost more in page faults than the transforms.
  thread_local Scratch scratch;
  scratch.reserve(size_t(w) * size_t(h), gains_.size());
  double* real = scratch.real.get();
  fftw_complex* spectrum = scratch.spectrum.get();
  std::fill(real, real + size_t(w) * size_t(h), 0.0);
  const int x0 = width_ / 2, y0 = height_ / 2;
  for (int y = 0; y < height_; ++y)
    std::copy_n(&contrast.values[size_t(y) * size_t(width_)], width_,
                real + size_t(y + y0) * size_t(w) + size_t(x0));
  fftw_execute_dft_r2c(plans_->forward, real, spectrum);
  for (size_t i = 0; i < gains_.size(); ++i) {
    spectrum[i][0] *= gains_[i];
    spectrum[i][1] *= gains_[i];
  }
  fftw_execute_dft_c2r(plans_->backward, spectrum, real);
  ContrastImage out(w, h);
  std::copy_n(real, out.values.size(), out.values.begin());
  return out;
}

ContrastImage csf_filtered(const ContrastImage& contrast, double ppd, bool oblique) {
  return CsfFilter(contrast.width, contrast.height, ppd, oblique).apply(contrast);
}

namespace {

// |r|^β as exp(β·ln|r|): the pooled sum takes one per pixel of the padded image (3 million for a
// 1024 × 768 stimulus), and this is about twice as fast as pow at a relative error near 1e-14.
double power_of_magnitude(double r, double beta) {
  return r == 0 ? 0.0 : std::exp(beta * std::log(std::abs(r)));
}

double sum_of_powers(const ContrastImage& filtered, double beta) {
  double sum = 0;
  for (double r : filtered.values) sum += power_of_magnitude(r, beta);
  return sum;
}

// The pooled response from the sum of |r|^β: pixel areas in square degrees.
double pooled(double sum_of_powers, double beta, double ppd) {
  return std::pow(sum_of_powers / (ppd * ppd), 1.0 / beta);
}

}  // namespace

double minkowski_pool(const ContrastImage& filtered, double beta, double ppd) {
  return pooled(sum_of_powers(filtered, beta), beta, ppd);
}

double response_jnd(const ContrastImage& contrast, double ppd, const DetectionModel& model) {
  return filtered_response_jnd(csf_filtered(contrast, ppd, model.oblique), ppd, model);
}

double filtered_response_jnd(const ContrastImage& filtered, double ppd,
                             const DetectionModel& model) {
  return model.gain * minkowski_pool(filtered, model.beta, ppd);
}

Observation observe(const ContrastImage& contrast, double ppd, const DetectionModel& model) {
  const ContrastImage filtered = csf_filtered(contrast, ppd, model.oblique);
  const double total = sum_of_powers(filtered, model.beta);
  Observation out{model.gain * pooled(total, model.beta, ppd),
                  ContrastImage(contrast.width, contrast.height)};
  const int x0 = contrast.width / 2, y0 = contrast.height / 2;
  for (int y = 0; y < contrast.height; ++y)
    for (int x = 0; x < contrast.width; ++x)
      out.share.at(x, y) =
          total > 0 ? power_of_magnitude(filtered.at(x + x0, y + y0), model.beta) / total : 0.0;
  return out;
}

}  // namespace countershade::observer
