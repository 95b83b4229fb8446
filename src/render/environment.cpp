#include "render/environment.h"

#include <algorithm>
#include <cmath>
#include <glm/vec2.hpp>
#include <numbers>

#include "core/fast_math.h"

namespace countershade {
namespace {

constexpr double kPi = std::numbers::pi;

double luminance(const glm::dvec3& c) { return 0.212671 * c.x + 0.715160 * c.y + 0.072169 * c.z; }

}  // namespace

glm::dvec3 equirect_direction(double u, double v) {
  double sin_phi, cos_phi, sin_theta, cos_theta;
  sincos_turns(u, sin_phi, cos_phi);            // φ = 2πu
  sincos_turns(0.5 * v, sin_theta, cos_theta);  // θ = πv
  return {sin_theta * sin_phi, cos_theta, -sin_theta * cos_phi};
}

namespace {

// The (u, v) of a unit direction: the inverse of equirect_direction.
glm::dvec2 equirect_coordinates(const glm::dvec3& d) {
  double u = std::atan2(d.x, -d.z) / (2.0 * kPi);
  if (u < 0) u += 1.0;
  return {u, std::acos(std::clamp(d.y, -1.0, 1.0)) / kPi};
}

}  // namespace

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
  find_constant_rows();
}

void EnvironmentMap::find_constant_rows() {
  rows_.clear();
  for (int y = 0; y < height_; ++y)
    for (int x = 1; x < width_; ++x)
      if (texel(x, y) != texel(0, y)) return;
  for (int y = 0; y < height_; ++y) rows_.push_back(texel(0, y));
}

EnvironmentMap EnvironmentMap::constant(const glm::dvec3& radiance) {
  Image image(8, 4, 3);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x)
      for (int k = 0; k < 3; ++k) image.at(x, y, k) = float(radiance[k]);
  EnvironmentMap map(image);
  for (auto& t : map.texels_) t = radiance;  // keep double precision
  map.find_constant_rows();
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
  const size_t n = size_t(width_) * height_;
  probability_.assign(n, 0.0);
  double total = 0;
  for (int y = 0; y < height_; ++y) {
    double sin_theta = std::sin(kPi * (y + 0.5) / height_);
    for (int x = 0; x < width_; ++x) {
      double w = luminance(texel(x, y)) * sin_theta + 1e-12;  // never exactly zero
      probability_[size_t(y) * width_ + x] = w;
      total += w;
    }
  }
  for (double& p : probability_) p /= total;
  // Vose's alias method: every slot holds its own texel with probability threshold, else its alias.
  alias_threshold_.assign(n, 1.0);
  alias_.resize(n);
  std::vector<double> scaled(n);
  std::vector<uint32_t> small, large;
  for (size_t i = 0; i < n; ++i) {
    alias_[i] = uint32_t(i);
    scaled[i] = probability_[i] * double(n);
    (scaled[i] < 1.0 ? small : large).push_back(uint32_t(i));
  }
  while (!small.empty() && !large.empty()) {
    uint32_t s = small.back(), l = large.back();
    small.pop_back();
    alias_threshold_[s] = scaled[s];
    alias_[s] = l;
    scaled[l] -= 1.0 - scaled[s];
    if (scaled[l] < 1.0) {
      large.pop_back();
      small.push_back(l);
    }
  }
}

glm::dvec3 EnvironmentMap::radiance_at(double u, double v) const {
  // Bilinear, wrapping in u and clamping in v.
  double fx = u * width_ - 0.5, fy = v * height_ - 0.5;
  int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
  double tx = fx - x0, ty = fy - y0;
  auto at = [&](int x, int y) -> const glm::dvec3& {
    x = x < 0 ? x + width_ : (x >= width_ ? x - width_ : x);  // u in [0, 1]: one wrap at most
    y = std::clamp(y, 0, height_ - 1);
    return texel(std::clamp(x, 0, width_ - 1), y);
  };
  return (1 - ty) * ((1 - tx) * at(x0, y0) + tx * at(x0 + 1, y0)) +
         ty * ((1 - tx) * at(x0, y0 + 1) + tx * at(x0 + 1, y0 + 1));
}

glm::dvec3 EnvironmentMap::radiance(const glm::dvec3& d) const {
  if (!rows_.empty()) {  // linear between rows, as the bilinear lookup of equal columns
    const double fy = std::acos(std::clamp(d.y, -1.0, 1.0)) / kPi * height_ - 0.5;
    const int y0 = int(std::floor(fy));
    const double ty = fy - y0;
    return (1 - ty) * rows_[size_t(std::clamp(y0, 0, height_ - 1))] +
           ty * rows_[size_t(std::clamp(y0 + 1, 0, height_ - 1))];
  }
  const glm::dvec2 uv = equirect_coordinates(d);
  return radiance_at(uv.x, uv.y);
}

// A uniform (u,v) point inside a texel has solid-angle density p / (sinθ · 2π/W · π/H).
double EnvironmentMap::pdf_of_texel(size_t index, double sin_theta) const {
  return probability_[index] * width_ * height_ / (2.0 * kPi * kPi * std::max(sin_theta, 1e-8));
}

EnvironmentMap::Sample EnvironmentMap::sample(double u1, double u2, double u3) const {
  const size_t n = probability_.size();
  double scaled = u1 * double(n);
  size_t slot = std::min(size_t(scaled), n - 1);
  size_t index = (scaled - double(slot)) < alias_threshold_[slot] ? slot : alias_[slot];
  int x = int(index % size_t(width_)), y = int(index / size_t(width_));
  double u = (x + u2) / width_, v = (y + u3) / height_;
  const glm::dvec3 d = equirect_direction(u, v);
  return {d, pdf_of_texel(index, std::sqrt(std::max(0.0, 1.0 - d.y * d.y))), radiance_at(u, v)};
}

double EnvironmentMap::pdf(const glm::dvec3& d) const {
  const glm::dvec2 uv = equirect_coordinates(d);
  int x = std::min(int(uv.x * width_), width_ - 1), y = std::min(int(uv.y * height_), height_ - 1);
  return pdf_of_texel(size_t(y) * width_ + x, std::sqrt(std::max(0.0, 1.0 - d.y * d.y)));
}

}  // namespace countershade
