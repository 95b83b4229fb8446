#include "render/camera.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

namespace countershade {

void resize(Camera& camera, std::optional<int> width, std::optional<int> height) {
  const double aspect = double(camera.width) / double(camera.height);
  if (width) camera.width = *width;
  if (height) camera.height = *height;
  if (width && !height) camera.height = std::max(1, int(std::lround(*width / aspect)));
  if (height && !width) camera.width = std::max(1, int(std::lround(*height * aspect)));
}

CameraRays::CameraRays(const Camera& camera) : camera_(camera) {
  forward_ = glm::normalize(camera.target - camera.eye);
  right_ = glm::normalize(glm::cross(forward_, camera.up));
  up_ = glm::cross(right_, forward_);
  half_height_ = camera.orthographic ? camera.ortho_height / 2
                                     : std::tan(glm::radians(camera.vertical_fov_deg) / 2);
  half_width_ = half_height_ * double(camera.width) / double(camera.height);
}

Ray CameraRays::ray(double x, double y) const {
  double sx = (2.0 * x / camera_.width - 1.0) * half_width_;
  double sy = (1.0 - 2.0 * y / camera_.height) * half_height_;
  if (camera_.orthographic) return {camera_.eye + sx * right_ + sy * up_, forward_};
  return {camera_.eye, glm::normalize(forward_ + sx * right_ + sy * up_)};
}

glm::dvec3 CameraRays::point_at_depth(double x, double y, double depth) const {
  const Ray r = ray(x, y);
  return r.origin + r.direction * (depth / glm::dot(r.direction, forward_));
}

unsigned CameraRays::outside(const glm::dvec3& p) const {
  // Which of the five half-spaces that bound what rays reach the point lies outside. The sides are
  // widened by a relative 1e-6 so that rounding never culls a triangle at the edge.
  constexpr double kSlack = 1 + 1e-6;
  const glm::dvec3 d = p - camera_.eye;
  const double z = glm::dot(d, forward_), x = glm::dot(d, right_), y = glm::dot(d, up_);
  const double w = kSlack * (camera_.orthographic ? half_width_ : half_width_ * z);
  const double h = kSlack * (camera_.orthographic ? half_height_ : half_height_ * z);
  return unsigned(x < -w) | unsigned(x > w) << 1 | unsigned(y < -h) << 2 | unsigned(y > h) << 3 |
         unsigned(z < 0) << 4;
}

bool CameraRays::may_see(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) const {
  return (outside(a) & outside(b) & outside(c)) == 0;
}

glm::dvec2 CameraRays::film_position(const glm::dvec3& p) const {
  const glm::dvec3 d = p - camera_.eye;
  const double depth = camera_.orthographic ? 1.0 : glm::dot(d, forward_);
  const double sx = glm::dot(d, right_) / depth, sy = glm::dot(d, up_) / depth;
  return {(sx / half_width_ + 1.0) * camera_.width / 2.0,
          (1.0 - sy / half_height_) * camera_.height / 2.0};
}

double CameraRays::eye_depth(const glm::dvec3& p) const {
  return glm::dot(p - camera_.eye, forward_);
}

glm::dvec3 CameraRays::towards_viewer(const glm::dvec3& p) const {
  return camera_.orthographic ? -forward_ : glm::normalize(camera_.eye - p);
}

}  // namespace countershade
