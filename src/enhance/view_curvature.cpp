#include "enhance/view_curvature.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "enhance/film_lookup.h"

namespace countershade {
namespace {

// The derivative of `value` across pixel i from its neighbours `before` and `after`: central where
// both are object pixels, one-sided where one is, 0 where neither is.
double derivative(bool has_before, bool has_after, double v_before, double v_i, double v_after) {
  if (has_before && has_after) return 0.5 * (v_after - v_before);
  if (has_after) return v_after - v_i;
  if (has_before) return v_i - v_before;
  return 0;
}

}  // namespace

double read_curvature_tau(const ParameterBag& bag) { return bag.number_in("tau", 1.0, 0.0, 1e6); }

ParameterDoc curvature_tau_doc() {
  return {"tau", "1", "τ in pixels: κ = tanh(τ·curvature of the screen-space normal field)"};
}

ViewCurvature::ViewCurvature(const View& view, double tau)
    : camera_(view.scene->camera),
      kappa_(view.render.gbuffer.width, view.render.gbuffer.height, 1) {
  const GBuffer& g = view.render.gbuffer;
  std::vector<glm::dvec2> field(g.normal.size(), glm::dvec2(0.0));
  object_.assign(g.normal.size(), 0);
  for (size_t i = 0; i < field.size(); ++i) {
    if (g.object[i] < 0) continue;
    const glm::dvec3 n(g.normal[i]);
    const double nz = std::max(-glm::dot(n, camera_.forward()), 1e-3);
    field[i] = -glm::dvec2(glm::dot(n, camera_.right()), glm::dot(n, camera_.up())) / nz;
    object_[i] = 1;
  }
  for (int y = 1; y + 1 < g.height; ++y)
    for (int x = 1; x + 1 < g.width; ++x) {
      const size_t i = g.index(x, y), above = i - size_t(g.width), below = i + size_t(g.width);
      if (!object_[i]) continue;
      const double dx =
          derivative(object_[i - 1], object_[i + 1], field[i - 1].x, field[i].x, field[i + 1].x);
      // Film rows grow downwards while the view's y axis points up.
      const double dy =
          derivative(object_[below], object_[above], field[below].y, field[i].y, field[above].y);
      kappa_.at(x, y) = float(std::tanh(-tau * (dx + dy)));
    }
}

double ViewCurvature::at(const glm::dvec3& p) const {
  const auto [sum, weight] =
      interpolate_in_mask<double>(camera_.film_position(p), kappa_.width, kappa_.height, object_,
                                  [&](size_t i) { return double(kappa_.pixels[i]); });
  return weight > 0 ? sum / weight : 0.0;
}

}  // namespace countershade
