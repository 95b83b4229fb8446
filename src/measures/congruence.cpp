#include "measures/congruence.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/gaussian.h"
#include "enhance/lightness.h"

namespace countershade {
namespace {

constexpr double kIsotropic = 1e-12;  // eigenvalue gap below which there is no orientation
constexpr double kNormalisingQuantile = 0.99;

bool is_foreground(float depth) { return std::isfinite(depth) && depth > 0; }

// Interior pixels: foreground, with all eight neighbours inside the image and foreground.
std::vector<char> interior_mask(const Image& depth) {
  const int w = depth.width, h = depth.height;
  std::vector<char> interior(size_t(w) * h, 0);
  for (int y = 1; y + 1 < h; ++y)
    for (int x = 1; x + 1 < w; ++x) {
      bool all = true;
      for (int dy = -1; dy <= 1 && all; ++dy)
        for (int dx = -1; dx <= 1 && all; ++dx) all = is_foreground(depth.at(x + dx, y + dy));
      interior[size_t(y) * w + x] = all;
    }
  return interior;
}

// Depth over the foreground mapped to [0, 1]; background pixels are 1.
std::vector<float> normalised_depth(const Image& depth) {
  float lo = INFINITY, hi = -INFINITY;
  for (float d : depth.pixels)
    if (is_foreground(d)) lo = std::min(lo, d), hi = std::max(hi, d);
  std::vector<float> out(depth.pixels.size(), 1.0f);
  for (size_t i = 0; i < out.size(); ++i)
    if (is_foreground(depth.pixels[i]))
      out[i] = hi > lo ? (depth.pixels[i] - lo) / (hi - lo) : 0.0f;
  return out;
}

// The flow of one field: per pixel the dominant orientation v (unit, or 0 where the tensor is
// isotropic) and the mean eigenvalue e, before normalisation.
struct Flow {
  std::vector<float> vx, vy, e;
};

// Central differences, (f(x+1) − f(x−1))/2, and one-sided differences at the border.
float derivative(const std::vector<float>& f, int i, int stride, int k, int n) {
  if (n < 2) return 0.0f;
  if (k == 0) return f[size_t(i + stride)] - f[size_t(i)];
  if (k == n - 1) return f[size_t(i)] - f[size_t(i - stride)];
  return 0.5f * (f[size_t(i + stride)] - f[size_t(i - stride)]);
}

// Dominant eigenvector and mean eigenvalue of [a b; b c].
void eigen(double a, double b, double c, float& vx, float& vy, float& e) {
  e = float(0.5 * (a + c));
  const double half = 0.5 * (a - c), root = std::sqrt(half * half + b * b);
  vx = vy = 0.0f;
  if (2 * root < kIsotropic) return;
  const double largest = 0.5 * (a + c) + root;
  // Two expressions of the same eigenvector; the longer one is the better conditioned.
  double ux = largest - c, uy = b, wx = b, wy = largest - a;
  if (ux * ux + uy * uy < wx * wx + wy * wy) ux = wx, uy = wy;
  const double length = std::hypot(ux, uy);
  vx = float(ux / length), vy = float(uy / length);
}

Flow flow(const std::vector<float>& field, const std::vector<char>& interior, int w, int h,
          double tensor_sigma) {
  const size_t n = field.size();
  std::vector<float> xx(n, 0.0f), xy(n, 0.0f), yy(n, 0.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int i = y * w + x;
      if (!interior[size_t(i)]) continue;  // products are 0 outside the interior
      const float gx = derivative(field, i, 1, x, w), gy = derivative(field, i, w, y, h);
      xx[size_t(i)] = gx * gx, xy[size_t(i)] = gx * gy, yy[size_t(i)] = gy * gy;
    }
  for (std::vector<float>* p : {&xx, &xy, &yy})
    gaussian_blur_exact(p->data(), p->data(), w, h, tensor_sigma, 1);
  Flow f{std::vector<float>(n), std::vector<float>(n), std::vector<float>(n)};
  for (size_t i = 0; i < n; ++i) eigen(xx[i], xy[i], yy[i], f.vx[i], f.vy[i], f.e[i]);
  return f;
}

// e divided by its 99th percentile over the interior and clamped to [0, 1] (0 if that is 0).
void normalise_magnitude(std::vector<float>& e, const std::vector<char>& interior) {
  std::vector<float> inside;
  for (size_t i = 0; i < e.size(); ++i)
    if (interior[i]) inside.push_back(e[i]);
  const double scale = percentile(std::move(inside), kNormalisingQuantile);
  for (float& v : e) v = scale > 0 ? float(std::clamp(double(v) / scale, 0.0, 1.0)) : 0.0f;
}

}  // namespace

double percentile(std::vector<float> values, double p) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const double h = double(values.size() - 1) * p;
  const size_t k = size_t(std::floor(h));
  if (k + 1 >= values.size()) return values.back();
  return values[k] + (h - double(k)) * (double(values[k + 1]) - double(values[k]));
}

Congruence congruence(const Image& lightness, const Image& depth,
                      const CongruenceOptions& options) {
  if (lightness.channels != 1 || depth.channels != 1 || lightness.width != depth.width ||
      lightness.height != depth.height)
    throw std::invalid_argument(
        "congruence: lightness and depth must be one-channel images of the same size");
  const int w = depth.width, h = depth.height;
  const std::vector<char> interior = interior_mask(depth);
  std::vector<float> shading(lightness.pixels.size());
  for (size_t i = 0; i < shading.size(); ++i) shading[i] = lightness.pixels[i] / 100.0f;
  Flow s = flow(shading, interior, w, h, options.tensor_sigma);
  Flow c = flow(normalised_depth(depth), interior, w, h, options.tensor_sigma);
  normalise_magnitude(s.e, interior);
  normalise_magnitude(c.e, interior);
  Congruence out;
  out.map = Image(w, h, 1);
  double agreement = 0, weight = 0;
  for (size_t i = 0; i < interior.size(); ++i) {
    if (!interior[i]) continue;
    const double alignment = std::abs(double(c.vx[i]) * s.vx[i] + double(c.vy[i]) * s.vy[i]);
    const double difference = double(c.e[i]) - s.e[i];
    const double d =
        options.penalty == CongruencePenalty::absolute ? std::abs(difference) : difference;
    const double term = c.e[i] * (1.0 - std::clamp(d, 0.0, 1.0)) * alignment;
    out.map.pixels[i] = float(term);
    agreement += term, weight += c.e[i];
    ++out.interior_pixels;
  }
  out.score = weight > 0 ? agreement / weight : 0.0;
  return out;
}

Congruence display_congruence(const Image& display, const DisplayEncoding& encoding, int bits,
                              const std::vector<float>& depth, const CongruenceOptions& options) {
  const LabPixels lab = display_to_lab(display, encoding, bits);
  Image lightness(display.width, display.height, 1);
  for (size_t i = 0; i < lab.size(); ++i) lightness.pixels[i] = float(lab[i].L);
  Image depth_image(display.width, display.height, 1);
  if (depth.size() != depth_image.pixels.size())
    throw std::invalid_argument("congruence: depth size differs from the image");
  std::copy(depth.begin(), depth.end(), depth_image.pixels.begin());
  return congruence(lightness, depth_image, options);
}

}  // namespace countershade
