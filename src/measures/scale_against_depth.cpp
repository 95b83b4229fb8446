#include "measures/scale_against_depth.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>
#include <map>

namespace countershade {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kMaxReachPx = 64;

// The crossing of `target` between samples a and b, log-linear where both are positive.
double crossing(double da, double va, double db, double vb, double target) {
  const double t = vb > 0 ? (std::log(va) - std::log(target)) / (std::log(va) - std::log(vb))
                          : (va - target) / (va - vb);
  return da + t * (db - da);
}

bool ground(float depth) { return std::isfinite(depth) && depth > 0; }

// Where the probe's ground meets one image row: a world point of the row's middle ground pixel,
// from its depth (the ground is horizontal and the camera not rolled, so the row is a line of
// constant world z and eye depth). False if the row has no ground pixel.
bool row_point(const ProbeImage& image, const CameraRays& rays, int y, glm::dvec3& point) {
  const int w = image.camera.width;
  std::vector<int> xs;
  for (int x = 0; x < w; ++x)
    if (ground(image.depth[size_t(y) * w + x])) xs.push_back(x);
  if (xs.empty()) return false;
  const int x = xs[xs.size() / 2];
  point = rays.point_at_depth(x + 0.5, y + 0.5, image.depth[size_t(y) * w + x]);
  return true;
}

// One side of an edge crossing row y at film x `edge`: the layer's magnitude against the distance
// along the edge's normal (|normal_x| per pixel along the row), out to `reach` pixels along the
// row.
double side_width(const ProbeImage& image, int y, double edge, double normal_x, double reach,
                  int side, double row_depth) {
  const int w = image.camera.width;
  std::vector<double> distance, magnitude;
  for (int x = side > 0 ? int(std::floor(edge - 0.5)) + 1 : int(std::ceil(edge - 0.5)) - 1;
       x >= 0 && x < w; x += side) {
    const double along = std::abs(x + 0.5 - edge);
    if (along > reach) break;
    const float depth = image.depth[size_t(y) * w + x];
    if (!ground(depth) || std::abs(depth - row_depth) > 0.1 * row_depth)
      return kNaN;  // another object
    distance.push_back(along * normal_x);
    magnitude.push_back(std::abs(double(image.layer[size_t(y) * w + x])));
  }
  return halo_width(distance, magnitude);
}

}  // namespace

double halo_width(std::span<const double> distance, std::span<const double> magnitude) {
  if (magnitude.empty()) return kNaN;
  const size_t peak =
      size_t(std::max_element(magnitude.begin(), magnitude.end()) - magnitude.begin());
  if (!(magnitude[peak] > 0)) return kNaN;
  const double target = magnitude[peak] / std::exp(1.0);
  for (size_t i = peak + 1; i < magnitude.size(); ++i)
    if (magnitude[i] < target)
      return crossing(distance[i - 1], magnitude[i - 1], distance[i], magnitude[i], target) -
             distance[peak];
  return kNaN;
}

std::vector<HaloSample> halo_samples(const ProbeImage& image, std::span<const double> edges_x,
                                     int row_step) {
  const CameraRays rays(image.camera);
  std::vector<HaloSample> out;
  for (int y = 0; y < image.camera.height; y += std::max(1, row_step)) {
    glm::dvec3 p;
    if (!row_point(image, rays, y, p)) continue;
    const double depth = rays.eye_depth(p);
    std::vector<double> film(edges_x.size());
    for (size_t k = 0; k < edges_x.size(); ++k)
      film[k] = rays.film_position({edges_x[k], p.y, p.z}).x;
    for (size_t k = 0; k < edges_x.size(); ++k) {
      const glm::dvec3 q{edges_x[k], p.y, p.z};
      const glm::dvec2 along =
          glm::normalize(rays.film_position(q - glm::dvec3(0, 0, 0.01 * depth)) -
                         rays.film_position(q + glm::dvec3(0, 0, 0.01 * depth)));
      const double normal_x = std::abs(along.y);  // the edge's normal is (along.y, −along.x)
      double sum = 0;
      int sides = 0;
      for (int side : {-1, 1}) {
        const bool has_next = side > 0 ? k + 1 < edges_x.size() : k > 0;
        const double next = has_next ? std::abs(film[k + size_t(side)] - film[k]) : 2 * kMaxReachPx;
        const double width =
            side_width(image, y, film[k], normal_x, std::min(0.5 * next, kMaxReachPx), side, depth);
        if (std::isfinite(width)) sum += width, ++sides;
      }
      if (sides) out.push_back({edges_x[k], depth, sum / sides});
    }
  }
  return out;
}

DepthSlope depth_slope(const std::vector<HaloSample>& samples, double min_width_px) {
  struct Sums {
    double n = 0, x = 0, y = 0;
  };
  std::map<double, Sums> edge;  // per edge, for its own intercept
  DepthSlope out;
  out.depth_min = std::numeric_limits<double>::infinity();
  for (const HaloSample& s : samples) {
    if (!(s.width_px >= min_width_px)) continue;
    Sums& e = edge[s.edge_x];
    e.n += 1, e.x += std::log(s.depth), e.y += std::log(s.width_px);
    ++out.samples;
    out.depth_min = std::min(out.depth_min, s.depth);
    out.depth_max = std::max(out.depth_max, s.depth);
  }
  double sxy = 0, sxx = 0;
  for (const HaloSample& s : samples) {
    if (!(s.width_px >= min_width_px)) continue;
    const Sums& e = edge.at(s.edge_x);
    const double x = std::log(s.depth) - e.x / e.n, y = std::log(s.width_px) - e.y / e.n;
    sxy += x * y, sxx += x * x;
  }
  out.slope = out.samples >= 3 && sxx > 0 ? sxy / sxx : kNaN;
  return out;
}

}  // namespace countershade
