// Cornsweet profiles (Purves et al.'s 2D-vs-3D comparison, docs/methods): two regions of equal
// lightness meet at an edge; near it, L* changes by ±A·exp(−|d|/w), with opposite signs on the
// two sides. A = λ·amplitude (ΔL*), w = σ.
//   mode "image":   the edge is the image's vertical centre line, d and w in pixels (a flat 2D
//                   stimulus when the view is a uniform field);
//   mode "surface": the edge is a 3D line (edge_point, edge_direction), d is the distance of each
//                   surface point from it and w is in world units; points whose normal lies
//                   within 60° of bright_normal take +, the others −. The profile is averaged
//                   over each pixel's samples, so silhouettes get no outline.

#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "core/color.h"
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
PixelDoubles image_profile(int w, int h, double width) {
  PixelDoubles profile(size_t(w) * h);
  const double centre = 0.5 * w;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double d = (x + 0.5) - centre;
      profile[size_t(y) * w + x] = (d > 0 ? 1.0 : -1.0) * std::exp(-std::abs(d) / width);
    }
  return profile;
}

// The signed profile side·exp(−d/w) across a 3D edge at a sample's surface point: d is the
// point's distance from the edge line, the side is + where the normal facing the camera lies
// within 60° of bright_normal.
class SurfaceProfile final : public SampleField {
 public:
  explicit SurfaceProfile(const CornsweetParameters& p)
      : point_(p.edge_point), direction_(glm::normalize(p.edge_direction)), bright_(glm::normalize(p.bright_normal)),
        width_(p.width) {}
  double value(const SampleHit& hit) const override {
    const glm::dvec3 offset = hit.point.position - point_;
    const double d = glm::length(offset - glm::dot(offset, direction_) * direction_);
    const glm::dvec3 normal = hit.back ? -hit.point.shading_normal : hit.point.shading_normal;
    return (glm::dot(normal, bright_) > 0.5 ? 1.0 : -1.0) * std::exp(-d / width_);
  }

 private:
  glm::dvec3 point_, direction_, bright_;
  double width_;
};

class SurfaceProfileStage final : public SurfaceStage {
 public:
  explicit SurfaceProfileStage(const CornsweetParameters& p) : field_(std::make_shared<SurfaceProfile>(p)) {}
  SampleFields fields() const override { return {field_}; }

 private:
  std::shared_ptr<const SurfaceProfile> field_;
};

// The surface profile per pixel, coverage-correct: the pixel's change is what the surface
// samples' change does to the pixel's luminance, to first order. With p̄ the profile averaged over
// all samples (background 0), a ΔL* of λ·A on the surface changes the pixel's L* by
// λ·A·p̄·(dY/dL* at the surface's L*) / (dY/dL* at the pixel's L*), and dY/dL* ∝ (L* + 16)².
// A pixel wholly on the surface gets λ·A·p̄; background pixels get nothing.
PixelDoubles surface_profile(const View& view, const std::vector<float>& profile) {
  const RenderResult& r = view.render;
  PixelDoubles amount(profile.size(), 0.0);
  for (size_t i = 0; i < amount.size(); ++i) {
    if (!(r.coverage[i] > 0)) continue;
    const double surface = cielab_lightness(double(r.surface_luminance[i]) / double(r.coverage[i])) + 16.0;
    const double pixel = cielab_lightness(double(r.luminance[i])) + 16.0;
    amount[i] = double(profile[i]) * (surface * surface) / (pixel * pixel);
  }
  return amount;
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
  std::shared_ptr<const SurfaceStage> surface_stage(const SurfaceContext&,
                                                    const MethodParameters& parameters) const override {
    const auto& p = parameters_as<CornsweetParameters>(parameters);
    return p.surface ? std::make_shared<SurfaceProfileStage>(p) : nullptr;
  }
  std::string label(const MethodParameters& parameters) const override {
    return name() + (parameters_as<CornsweetParameters>(parameters).surface ? "-surface" : "-image");
  }

  std::unique_ptr<PreparedEnhancement> prepare(const PrepareContext& context,
                                               const MethodParameters& parameters) const override {
    const auto& p = parameters_as<CornsweetParameters>(parameters);
    const View& view = *context.view;
    if (p.surface && !view.scene) throw InputError("cornsweet: the surface mode needs a rendered scene");
    if (p.surface && context.fields.size() != 1)
      throw std::logic_error("cornsweet: the view was not rendered for these parameters (render it for a plan with them)");
    LightnessChange change;
    change.amount = p.surface ? surface_profile(view, *context.fields[0])
                              : image_profile(view.width(), view.height(), p.width);
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
