#include "render/environment.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace countershade {
namespace {

constexpr double kPi = std::numbers::pi;

double luminance(const glm::dvec3& c) { return 0.212671 * c.x + 0.715160 * c.y + 0.072169 * c.z; }

// Index i with cdf[i] <= u < cdf[i+1] in a cdf of n+1 entries starting at 0 and ending at 1.
size_t find_interval(const std::vector<double>& cdf, size_t begin, size_t n, double u) {
  auto first = cdf.begin() + long(begin), last = first + long(n) + 1;
  auto it = std::upper_bound(first, last, u);
  size_t i = size_t(it - first);
  return std::clamp<size_t>(i == 0 ? 0 : i - 1, 0, n - 1);
}

}  // namespace

glm::dvec3 equirect_direction(double u, double v) {
  double phi = 2.0 * kPi * u, theta = kPi * v;
  return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

EnvironmentMap::EnvironmentMap(const Image& image) : width_(image.width), height_(image.height) {
  texels_.resize(size_t(width_) * height_);
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      glm::dvec3 c;
      for (int k = 0; k < 3; ++k) c[k] = image.at(x, y, std::min(k, image.channels - 1));
      // Negative or non-finite texels would break sampling; treat them as black.
      for (int k = 0; k < 3; ++k) c[k] = std::isfinite(c[k]) ? std::max(c[k], 0.0) : 0.0;
      texels_[size_t(y) * width_ + x] = c;
    }
  build_distribution();
}

EnvironmentMap EnvironmentMap::constant(const glm::dvec3& radiance) {
  Image image(8, 4, 3);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x)
      for (int k = 0; k < 3; ++k) image.at(x, y, k) = float(radiance[k]);
  EnvironmentMap map(image);
  for (auto& t : map.texels_) t = radiance;  // keep double precision
  return map;
}

EnvironmentMap EnvironmentMap::sky(const SkyParameters& sky, int width, int height) {
  Image image(width, height, 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      glm::dvec3 d = equirect_direction((x + 0.5) / width, (y + 0.5) / height);
      glm::dvec3 c;
      if (d.y >= 0) {
        double t = std::sqrt(d.y);
        c = sky.horizon * (1.0 - t) + sky.zenith * t;
      } else {
        double t = std::min(1.0, -d.y * 8.0);  // short blend below the horizon
        c = sky.horizon * (1.0 - t) + sky.ground * t;
      }
      for (int k = 0; k < 3; ++k) image.at(x, y, k) = float(c[k]);
    }
  return EnvironmentMap(image);
}

void EnvironmentMap::build_distribution() {
  conditional_cdf_.assign(size_t(height_) * (width_ + 1), 0.0);
  row_weight_.assign(height_, 0.0);
  marginal_cdf_.assign(height_ + 1, 0.0);
  for (int y = 0; y < height_; ++y) {
    double sin_theta = std::sin(kPi * (y + 0.5) / height_);
    double* cdf = &conditional_cdf_[size_t(y) * (width_ + 1)];
    for (int x = 0; x < width_; ++x) cdf[x + 1] = cdf[x] + luminance(texel(x, y)) * sin_theta + 1e-12;
    row_weight_[y] = cdf[width_];
    for (int x = 1; x <= width_; ++x) cdf[x] /= row_weight_[y];
    marginal_cdf_[y + 1] = marginal_cdf_[y] + row_weight_[y];
  }
  total_weight_ = marginal_cdf_[height_];
  for (int y = 1; y <= height_; ++y) marginal_cdf_[y] /= total_weight_;
}

glm::dvec3 EnvironmentMap::radiance(const glm::dvec3& d) const {
  double u = std::atan2(d.x, -d.z) / (2.0 * kPi);
  if (u < 0) u += 1.0;
  double v = std::acos(std::clamp(d.y, -1.0, 1.0)) / kPi;
  // Bilinear, wrapping in u and clamping in v.
  double fx = u * width_ - 0.5, fy = v * height_ - 0.5;
  int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
  double tx = fx - x0, ty = fy - y0;
  auto at = [&](int x, int y) -> const glm::dvec3& {
    x = ((x % width_) + width_) % width_;
    y = std::clamp(y, 0, height_ - 1);
    return texel(x, y);
  };
  return (1 - ty) * ((1 - tx) * at(x0, y0) + tx * at(x0 + 1, y0)) +
         ty * ((1 - tx) * at(x0, y0 + 1) + tx * at(x0 + 1, y0 + 1));
}

EnvironmentMap::Sample EnvironmentMap::sample(double u1, double u2) const {
  size_t y = find_interval(marginal_cdf_, 0, size_t(height_), u1);
  size_t row = y * (width_ + 1);
  size_t x = find_interval(conditional_cdf_, row, size_t(width_), u2);
  // Uniform position inside the chosen texel, reusing the leftover of u1 and u2.
  double dy = (u1 - marginal_cdf_[y]) / std::max(marginal_cdf_[y + 1] - marginal_cdf_[y], 1e-300);
  double dx = (u2 - conditional_cdf_[row + x]) /
              std::max(conditional_cdf_[row + x + 1] - conditional_cdf_[row + x], 1e-300);
  double u = (x + std::clamp(dx, 0.0, 1.0)) / width_, v = (y + std::clamp(dy, 0.0, 1.0)) / height_;
  glm::dvec3 d = equirect_direction(u, v);
  return {d, pdf(d)};
}

double EnvironmentMap::pdf(const glm::dvec3& d) const {
  double u = std::atan2(d.x, -d.z) / (2.0 * kPi);
  if (u < 0) u += 1.0;
  double v = std::acos(std::clamp(d.y, -1.0, 1.0)) / kPi;
  int x = std::min(int(u * width_), width_ - 1), y = std::min(int(v * height_), height_ - 1);
  double sin_theta = std::sqrt(std::max(0.0, 1.0 - d.y * d.y));
  size_t row = size_t(y) * (width_ + 1);
  double p_texel = (row_weight_[y] / total_weight_) *
                   (conditional_cdf_[row + x + 1] - conditional_cdf_[row + x]);
  // Uniform (u,v) inside a texel has solid-angle density p / (sinθ · 2π/W · π/H).
  return p_texel * width_ * height_ / (2.0 * kPi * kPi * std::max(sin_theta, 1e-8));
}

}  // namespace countershade
