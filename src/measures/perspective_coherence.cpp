#include "measures/perspective_coherence.h"

#include <cmath>
#include <glm/geometric.hpp>
#include <limits>

#include "enhance/lightness.h"
#include "render/scene_animation.h"

namespace countershade {
namespace {

bool on_surface(const std::vector<float>& depth, size_t i) {
  return std::isfinite(depth[i]) && depth[i] > 0;
}

// Whether pixel i sees `object` within 10 % of eye depth `depth`: the test every pixel of a
// neighbourhood must pass, in the first frame (interior) as in the moved one (lookup).
bool sees(const View& v, size_t i, int object, double depth) {
  return on_surface(v.depth, i) && v.object_at(i) == object &&
         std::abs(double(v.depth[i]) / depth - 1.0) <= 0.1;
}

// Whether pixel (x, y) and its 3×3 neighbourhood all see one object within 10 % of the pixel's
// depth, as `lookup` asks of the moved frame: a pixel beside another object, the background or a
// fold of its own object shares its area with it, so its value is not that of one surface point.
bool interior(const View& v, int x, int y) {
  if (x < 1 || y < 1 || x + 1 >= v.width() || y + 1 >= v.height()) return false;
  const size_t centre = size_t(y) * size_t(v.width()) + size_t(x);
  const int object = v.object_at(centre);
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx)
      if (!sees(v, size_t(y + dy) * size_t(v.width()) + size_t(x + dx), object, v.depth[centre]))
        return false;
  return true;
}

// Catmull–Rom weights of the four samples around a fractional position t in [0, 1).
void catmull_rom(double t, double w[4]) {
  const double t2 = t * t, t3 = t2 * t;
  w[0] = 0.5 * (-t3 + 2 * t2 - t);
  w[1] = 0.5 * (3 * t3 - 5 * t2 + 2);
  w[2] = 0.5 * (-3 * t3 + 4 * t2 + t);
  w[3] = 0.5 * (t3 - t2);
}

// The value of `values` at film position `film` of `v`, interpolated bicubically (Catmull–Rom, so
// that detail near the pixel scale survives the resampling better than bilinearly), if the 4×4
// pixels there all see `object` within 10 % of that depth (so no other surface mixes in, not even
// one just behind a silhouette) and the four nearest see the point of eye depth `depth`.
bool lookup(const View& v, const glm::dvec2& film, double depth, int object,
            std::span<const float> values, double& out) {
  const double fx = film.x - 0.5, fy = film.y - 0.5;
  const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
  if (x0 < 1 || y0 < 1 || x0 + 2 >= v.width() || y0 + 2 >= v.height()) return false;
  const double tx = fx - x0, ty = fy - y0;
  double inverse_depth = 0, value = 0, wx[4], wy[4];
  catmull_rom(tx, wx);
  catmull_rom(ty, wy);
  for (int dy = -1; dy <= 2; ++dy)
    for (int dx = -1; dx <= 2; ++dx) {
      const size_t i = size_t(y0 + dy) * size_t(v.width()) + size_t(x0 + dx);
      if (!sees(v, i, object, depth)) return false;
      value += wx[dx + 1] * wy[dy + 1] * double(values[i]);
      if (dx >= 0 && dx <= 1 && dy >= 0 && dy <= 1)  // 1/depth is affine across a plane's image
        inverse_depth += (dx ? tx : 1 - tx) * (dy ? ty : 1 - ty) / double(v.depth[i]);
    }
  if (std::abs(inverse_depth * depth - 1.0) > 0.01) return false;  // another surface is in front
  out = value;
  return true;
}

}  // namespace

Camera dollied(const Camera& camera, double fraction) {
  Camera moved = camera;
  moved.eye = camera.eye + fraction * (camera.target - camera.eye);
  return moved;
}

std::vector<float> enhancement_layer(const View& view, const Image& display) {
  const LabPixels enhanced = display_to_lab(display, view.encoding, view.bits);
  std::vector<float> layer(enhanced.size());
  for (size_t i = 0; i < layer.size(); ++i) layer[i] = float(enhanced[i].L - view.lab[i].L);
  return layer;
}

CarryPoint carry_between_frames(const Scene& base, int from, int to) {
  const double t0 = base.animation->time_of(from), t1 = base.animation->time_of(to);
  return [&base, t0, t1](const glm::dvec3& p, int object) {
    return object < 0 ? p : carry_point(base, size_t(object), t0, t1, p);
  };
}

Reprojection reprojection_rms(const View& first, std::span<const float> first_values,
                              const View& moved, std::span<const float> moved_values,
                              const CarryPoint& carry, std::vector<float>* differences) {
  if (differences)
    differences->assign(first_values.size(), std::numeric_limits<float>::quiet_NaN());
  const CameraRays a(first.scene->camera), b(moved.scene->camera);
  double sum = 0;
  size_t count = 0;
  for (int y = 0; y < first.height(); ++y)
    for (int x = 0; x < first.width(); ++x) {
      if (!interior(first, x, y)) continue;
      const size_t i = size_t(y) * size_t(first.width()) + size_t(x);
      glm::dvec3 p = a.point_at_depth(x + 0.5, y + 0.5, first.depth[i]);
      const int object = first.object_at(i);
      if (carry) p = carry(p, object);
      double value;
      if (b.eye_depth(p) <= 0 ||
          !lookup(moved, b.film_position(p), b.eye_depth(p), object, moved_values, value))
        continue;
      const double d = double(first_values[i]) - value;
      if (differences) (*differences)[i] = float(std::abs(d));
      sum += d * d;
      ++count;
    }
  return {count ? std::sqrt(sum / double(count)) : 0.0, count};
}

Reprojection rms_where_stable(const std::vector<float>& differences,
                              const std::vector<float>& plain_differences, double tolerance) {
  double sum = 0;
  Reprojection out;
  for (size_t i = 0; i < differences.size(); ++i)
    if (!std::isnan(differences[i]) && plain_differences[i] <= tolerance) {
      sum += double(differences[i]) * differences[i];
      ++out.pixels;
    }
  out.rms = out.pixels ? std::sqrt(sum / double(out.pixels)) : 0.0;
  return out;
}

}  // namespace countershade
