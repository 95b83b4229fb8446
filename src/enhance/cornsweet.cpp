#include "enhance/cornsweet.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "core/error.h"

namespace countershade {
namespace {

class CornsweetPrepared final : public PreparedEnhancement {
 public:
  CornsweetPrepared(const View& view, std::vector<double> profile, double amplitude, nlohmann::json parameters)
      : view_(view), profile_(std::move(profile)), amplitude_(amplitude), parameters_(std::move(parameters)) {}
  Composed compose(double lambda) const override {
    std::vector<double> delta(profile_.size());
    for (size_t i = 0; i < delta.size(); ++i) delta[i] = lambda * amplitude_ * profile_[i];
    return compose_lightness(view_.display, view_.lab, delta, view_.encoding);
  }
  nlohmann::json parameters() const override { return parameters_; }

 private:
  const View& view_;
  std::vector<double> profile_;  // signed exp(−|d|/w) per pixel
  double amplitude_;
  nlohmann::json parameters_;
};

}  // namespace

void CornsweetMethod::validate(const MethodOptions& o) const {
  if (o.cornsweet_mode != "image" && o.cornsweet_mode != "surface")
    throw InputError("cornsweet: mode must be image or surface");
  if (!(o.cornsweet_amplitude > 0) || !std::isfinite(o.cornsweet_amplitude))
    throw InputError("cornsweet: amplitude must be a positive ΔL*");
  if (o.cornsweet_mode == "image" && !(o.sigma_px && *o.sigma_px > 0))
    throw InputError("cornsweet: the image mode needs a positive width sigma_px");
  if (o.cornsweet_mode == "surface") {
    if (!(o.sigma && *o.sigma > 0)) throw InputError("cornsweet: the surface mode needs a positive width sigma");
    if (glm::length(o.edge_direction) < 1e-9 || glm::length(o.bright_normal) < 1e-9)
      throw InputError("cornsweet: edge_direction and bright_normal must not be zero");
  }
}

std::unique_ptr<PreparedEnhancement> CornsweetMethod::prepare(const View& view, const MethodOptions& o) const {
  validate(o);
  const int w = view.width(), h = view.height();
  std::vector<double> profile(size_t(w) * h, 0.0);
  if (o.cornsweet_mode == "image") {
    const double centre = 0.5 * w;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        double d = (x + 0.5) - centre;  // the edge lies between the two middle columns
        profile[size_t(y) * w + x] = (d > 0 ? 1.0 : -1.0) * std::exp(-std::abs(d) / *o.sigma_px);
      }
  } else {
    if (!view.scene) throw InputError("cornsweet: the surface mode needs a rendered scene");
    const GBuffer& g = view.render.gbuffer;
    const glm::dvec3 dir = glm::normalize(o.edge_direction), bright = glm::normalize(o.bright_normal);
    for (size_t i = 0; i < profile.size(); ++i) {
      if (g.object[i] < 0) continue;
      const TriangleMesh& mesh = view.scene->objects[size_t(g.object[i])].mesh;
      const glm::uvec3& t = mesh.triangles[size_t(g.triangle[i])];
      double b1 = g.barycentrics[i].x, b2 = g.barycentrics[i].y;
      glm::dvec3 p = (1 - b1 - b2) * glm::dvec3(mesh.positions[t.x]) + b1 * glm::dvec3(mesh.positions[t.y]) +
                     b2 * glm::dvec3(mesh.positions[t.z]);
      glm::dvec3 offset = p - o.edge_point;
      double d = glm::length(offset - glm::dot(offset, dir) * dir);
      double side = glm::dot(glm::dvec3(g.normal[i]), bright) > 0.5 ? 1.0 : -1.0;
      profile[i] = side * std::exp(-d / *o.sigma);
    }
  }
  nlohmann::json parameters = {{"mode", o.cornsweet_mode}, {"amplitude_per_lambda", o.cornsweet_amplitude},
                               {"width", o.cornsweet_mode == "image" ? *o.sigma_px : *o.sigma}};
  return std::make_unique<CornsweetPrepared>(view, std::move(profile), o.cornsweet_amplitude, parameters);
}

}  // namespace countershade
