#pragma once
// The image-computable detection model (docs/observer.md): a contrast image, filtered by the
// contrast sensitivity function in the frequency domain at the viewing condition's pixels per
// degree, and pooled over pixels by a Minkowski sum into a response in JND units (1 JND: the
// threshold, 84 % correct in two-interval forced choice).

#include <cstddef>
#include <memory>
#include <vector>

namespace countershade::observer {

// Contrast per pixel, (L − L̄) / L̄, rows top to bottom.
struct ContrastImage {
  int width = 0, height = 0;
  std::vector<double> values;

  ContrastImage() = default;
  ContrastImage(int w, int h) : width(w), height(h), values(size_t(w) * size_t(h), 0.0) {}
  double& at(int x, int y) { return values[size_t(y) * size_t(width) + size_t(x)]; }
  double at(int x, int y) const { return values[size_t(y) * size_t(width) + size_t(x)]; }
};

struct DetectionModel {
  double gain = 1;    // scales the pooled response into JND
  double beta = 2.5;  // the Minkowski exponent
  bool oblique = false;
};

// The model fitted to the ModelFest thresholds (fit_modelfest in observer/modelfest.h, without
// the oblique effect, which the fit does not need; docs/observer.md). A test fits it again and
// compares.
constexpr DetectionModel kModelfestModel{0.864, 2.55, false};

// The contrast sensitivity filter for one image size and viewing condition: its gains and FFTW's
// plans are made once, so that each image then costs one transform pair (a stimulus set holds
// hundreds of images of one size). apply() may run on several threads at once.
class CsfFilter {
 public:
  CsfFilter(int width, int height, double ppd, bool oblique);
  ~CsfFilter();
  CsfFilter(const CsfFilter&) = delete;
  CsfFilter& operator=(const CsfFilter&) = delete;

  // The image, surrounded by as much zero contrast again on every side (the mean-luminance field
  // a stimulus is shown in, so that its edges do not wrap around), filtered by the contrast
  // sensitivity function (and the oblique effect, if asked). The result is 2·width × 2·height,
  // the image at its centre. Throws std::invalid_argument for an image of another size.
  ContrastImage apply(const ContrastImage& contrast) const;

  int width() const { return width_; }
  int height() const { return height_; }
  double ppd() const { return ppd_; }

 private:
  struct Plans;
  int width_, height_;
  double ppd_;
  std::vector<double> gains_;  // per frequency of the padded transform, FFTW's scaling included
  std::unique_ptr<Plans> plans_;
};

// CsfFilter(contrast's size, ppd, oblique).apply(contrast), for a single image.
ContrastImage csf_filtered(const ContrastImage& contrast, double ppd, bool oblique);

// (Σ |r|^β · A)^(1/β) over the pixels, A the area of a pixel in square degrees, so that the
// response of a pattern does not depend on the resolution it is sampled at.
double minkowski_pool(const ContrastImage& filtered, double beta, double ppd);

// The response in JND: gain × the pooled filtered contrast.
double response_jnd(const ContrastImage& contrast, double ppd, const DetectionModel& model);
// The same from an image already filtered (CsfFilter::apply).
double filtered_response_jnd(const ContrastImage& filtered, double ppd,
                             const DetectionModel& model);

struct Observation {
  double jnd = 0;
  // Each pixel's share of the pooled sum, |r|^β / Σ|r|^β, on the image's own pixels (the shares
  // of the surround, where filtered contrast spreads, are left out, so these may sum below 1).
  ContrastImage share;
};
Observation observe(const ContrastImage& contrast, double ppd, const DetectionModel& model);

}  // namespace countershade::observer
