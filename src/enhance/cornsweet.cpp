// Cornsweet profiles (Purves et al.'s 2D-vs-3D comparison, docs/methods): two regions of equal
// lightness meet at an edge; near it, L* changes by ±A·exp(−|d|/w), with opposite signs on the
// two sides. A = λ·amplitude (ΔL*), w = σ.
//   mode "image":   the edge is the image's vertical centre line, d and w in pixels (a flat 2D
//                   stimulus when the view is a uniform field);
//   mode "surface": the edge is a 3D line (edge_point, edge_direction), d is the distance of each
//                   pixel's surface point from it and w is in world units; pixels whose normal
//                   lies within 60° of bright_normal take +, the others −.

#include <cmath>

#include <glm/geometric.hpp>

#include "core/error.h"
#include "enhance/lightness.h"
#include "render/shading.h"

namespace countershade {
namespace {

struct CornsweetParameters final : MethodParameters {
  bool surface = false;
  double amplitude = 4.0;  // ΔL* per unit of λ
  double width = 0;        // σ: pixels (image) or world units (surface)
  glm::dvec3 edge_point{0.0}, edge_direction{1, 0, 0}, bright_normal{0, 0, 1};
};

// Signed exp(−|d|/w) per pixel, the edge between the two middle columns.
std::vector<double> image_profile(int w, int h, double width) {
  std::vector<double> profile(size_t(w) * h);
  const double centre = 0.5 * w;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double d = (x + 0.5) - centre;
      profile[size_t(y) * w + x] = (d > 0 ? 1.0 : -1.0) * std::exp(-std::abs(d) / width);
    }
  return profile;
}

// The same across a 3D edge, from each pixel's hit point (0 for background).
std::vector<double> surface_profile(const View& view, const CornsweetParameters& p) {
  const GBuffer& g = view.render.gbuffer;
  std::vector<double> profile(size_t(g.width) * g.height, 0.0);
  const glm::dvec3 dir = glm::normalize(p.edge_direction), bright = glm::normalize(p.bright_normal);
  for (size_t i = 0; i < profile.size(); ++i) {
    if (g.object[i] < 0) continue;
    const glm::dvec3 point = surface_point(*view.scene, unsigned(g.object[i]), unsigned(g.triangle[i]),
                                           g.barycentrics[i].x, g.barycentrics[i].y).position;
    const glm::dvec3 offset = point - p.edge_point;
    const double d = glm::length(offset - glm::dot(offset, dir) * dir);
    const double side = glm::dot(glm::dvec3(g.normal[i]), bright) > 0.5 ? 1.0 : -1.0;
    profile[i] = side * std::exp(-d / p.width);
  }
  return profile;
}

class CornsweetMethod final : public EnhancementMethod {
 public:
  std::string name() const override { return "cornsweet"; }
  std::string summary() const override { return "Cornsweet profile across an edge, in the image or on a surface"; }
  MethodAxes axes() const override {
    return {"amplitude A = λ·amplitude (ΔL*)",
            {{"sigma_px", "px", "profile width w (image mode)"}, {"sigma", "world units", "profile width w (surface mode)"}}};
  }
  std::vector<ParameterDoc> parameter_docs() const override {
    return {{"mode", "image", "image: the edge is the image's vertical centre line; surface: a 3D edge"},
            {"amplitude", "4", "ΔL* per unit of λ"},
            {"sigma_px", "", "width w in pixels (image mode)"},
            {"sigma", "", "width w in world units (surface mode)"},
            {"edge_point", "0,0,0", "a point on the 3D edge (surface mode)"},
            {"edge_direction", "1,0,0", "the edge's direction (surface mode)"},
            {"bright_normal", "0,0,1", "normals within 60° of it take the bright side (surface mode)"}};
  }

  std::shared_ptr<const MethodParameters> parse(const ParameterBag& bag) const override {
    auto p = std::make_shared<CornsweetParameters>();
    p->surface = bag.choice("mode", "image", {"image", "surface"}) == "surface";
    p->amplitude = bag.number("amplitude", 4.0);
    const std::string width_key = p->surface ? "sigma" : "sigma_px", other = p->surface ? "sigma_px" : "sigma";
    if (bag.has(other))
      bag.fail(other, std::string("is the width of the ") + (p->surface ? "image" : "surface") + " mode; the " +
                          (p->surface ? "surface" : "image") + " mode takes " + width_key);
    p->width = bag.number(width_key, 0.0);
    if (p->surface) {
      p->edge_point = bag.vec3("edge_point", p->edge_point);
      p->edge_direction = bag.vec3("edge_direction", p->edge_direction);
      p->bright_normal = bag.vec3("bright_normal", p->bright_normal);
    }
    bag.finish(name());
    if (!(p->amplitude > 0)) bag.fail("amplitude", "must be a positive ΔL*");
    if (!(p->width > 0)) bag.fail(width_key, "the " + std::string(p->surface ? "surface" : "image") + " mode needs a positive width");
    if (glm::length(p->edge_direction) < 1e-9) bag.fail("edge_direction", "must not be zero");
    if (glm::length(p->bright_normal) < 1e-9) bag.fail("bright_normal", "must not be zero");
    return p;
  }

  RenderRequest request(const MethodParameters& parameters) const override {
    RenderRequest r;
    r.scene = parameters_as<CornsweetParameters>(parameters).surface;
    return r;
  }
  std::string label(const MethodParameters& parameters) const override {
    return name() + (parameters_as<CornsweetParameters>(parameters).surface ? "-surface" : "-image");
  }

  std::unique_ptr<PreparedEnhancement> prepare(const PrepareContext& context,
                                               const MethodParameters& parameters) const override {
    const auto& p = parameters_as<CornsweetParameters>(parameters);
    const View& view = *context.view;
    if (p.surface && !view.scene) throw InputError("cornsweet: the surface mode needs a rendered scene");
    LightnessChange change;
    change.amount = p.surface ? surface_profile(view, p) : image_profile(view.width(), view.height(), p.width);
    change.factor = p.amplitude;
    nlohmann::json record = {{"mode", p.surface ? "surface" : "image"}, {"amplitude_per_lambda", p.amplitude},
                             {"width", p.width}};
    return std::make_unique<LightnessPrepared>(context.view, std::move(change), std::move(record),
                                               std::vector<std::pair<std::string, Image>>{}, context.threads);
  }
};

}  // namespace

std::unique_ptr<const EnhancementMethod> make_cornsweet_method() { return std::make_unique<CornsweetMethod>(); }

}  // namespace countershade
