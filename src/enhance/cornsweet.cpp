// Cornsweet profiles (Purves et al.'s 2D-vs-3D comparison, docs/methods): two regions of equal
// lightness meet at an edge; near it L* rises on one side and falls on the other, by the profile
// of enhance/cornsweet_profile.h times λ.
//   mode "image":   the edge is the image's vertical centre line, d and w in pixels (a flat 2D
//                   stimulus when the view is a uniform field);
//   mode "surface": the edge is a 3D line (edge_point, edge_direction), d is the distance of each
//                   surface point from it and w is in world units; points whose normal lies
//                   within 60° of bright_normal take the bright side, the others the dark one.
//                   The profile is averaged over each pixel's samples, so silhouettes get no
//                   outline.

#include <cmath>
#include <glm/geometric.hpp>
#include <stdexcept>

#include "core/color.h"
#include "core/error.h"
#include "enhance/cornsweet_profile.h"
#include "enhance/lightness.h"
#include "render/shading.h"

namespace countershade {
namespace {

struct CornsweetParameters final : MethodParameters {
  bool surface = false;
  double factor =
      4.0;  // ΔL* per unit of λ: `amplitude`, or 1 where the edge values give the profile's
  CornsweetProfile profile;
  glm::dvec3 edge_point{0.0}, edge_direction{1, 0, 0}, bright_normal{0, 0, 1};
};

// The profile across a 3D edge at a sample's surface point: d is the point's distance from the
// edge line, the side is the bright one where the normal facing the camera lies within 60° of
// bright_normal.
class SurfaceProfile final : public SampleField {
 public:
  explicit SurfaceProfile(const CornsweetParameters& p)
      : profile_(p.profile),
        point_(p.edge_point),
        direction_(glm::normalize(p.edge_direction)),
        bright_(glm::normalize(p.bright_normal)) {}
  double value(const SampleHit& hit) const override {
    const glm::dvec3 offset = hit.point.position - point_;
    const double d = glm::length(offset - glm::dot(offset, direction_) * direction_);
    const glm::dvec3 normal = hit.back ? -hit.point.shading_normal : hit.point.shading_normal;
    return profile_.at(d, glm::dot(normal, bright_) > 0.5);
  }

 private:
  CornsweetProfile profile_;
  glm::dvec3 point_, direction_, bright_;
};

class SurfaceProfileStage final : public SurfaceStage {
 public:
  explicit SurfaceProfileStage(const CornsweetParameters& p)
      : field_(std::make_shared<SurfaceProfile>(p)) {}
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
    const double surface =
        cielab_lightness(double(r.surface_luminance[i]) / double(r.coverage[i])) + 16.0;
    const double pixel = cielab_lightness(double(r.luminance[i])) + 16.0;
    amount[i] = double(profile[i]) * (surface * surface) / (pixel * pixel);
  }
  return amount;
}

// The profile's width: sigma_px in the image mode, sigma on the surface.
double read_width(const ParameterBag& bag, bool surface) {
  const std::string key = surface ? "sigma" : "sigma_px", other = surface ? "sigma_px" : "sigma";
  if (bag.has(other))
    bag.fail(other, std::string("is the width of the ") + (surface ? "image" : "surface") +
                        " mode; the " + (surface ? "surface" : "image") + " mode takes " + key);
  const double width = bag.number(key, 0.0);
  if (!(width > 0))
    bag.fail(key,
             "the " + std::string(surface ? "surface" : "image") + " mode needs a positive width");
  return width;
}

// The power profile's edge values and plateau (in L*), where given: they then set the profile's
// size in place of the amplitude.
void read_edge_values(const ParameterBag& bag, CornsweetParameters& p) {
  if (bag.has("edges") != bag.has("plateau"))
    bag.fail(bag.has("edges") ? "edges" : "plateau", "edges and plateau are given together");
  if (!bag.has("edges")) return;
  if (bag.has("amplitude"))
    bag.fail("amplitude", "edges and plateau give the profile's size; leave amplitude out");
  const std::vector<double> edges = bag.numbers("edges", {});
  const double plateau = bag.number("plateau", 50.0);
  if (edges.size() != 2)
    bag.fail("edges", "needs two L* values: the dark (left) and the bright (right) edge");
  if (!(edges[0] >= 0 && edges[0] <= 100 && edges[1] >= 0 && edges[1] <= 100))
    bag.fail("edges", "must lie in [0, 100] (L*)");
  if (!(plateau >= 0 && plateau <= 100)) bag.fail("plateau", "must lie in [0, 100] (L*)");
  p.factor = 1.0;
  p.profile.dark = edges[0] - plateau;
  p.profile.bright = edges[1] - plateau;
}

class CornsweetMethod final : public EnhancementMethod {
 public:
  std::string name() const override { return "cornsweet"; }
  std::string summary() const override {
    return "Cornsweet profile across an edge, in the image or on a surface";
  }
  MethodAxes axes() const override {
    return {"the profile times λ: ±λ·amplitude at the edge, or λ·(edge − plateau) (ΔL*)",
            {{"sigma_px", "px", "profile width w (image mode)"},
             {"sigma", "world units", "profile width w (surface mode)"}}};
  }
  std::vector<ParameterDoc> parameter_docs() const override {
    return {
        {"mode", "image",
         "image: the edge is the image's vertical centre line; surface: a 3D edge"},
        {"profile", "exponential",
         "exponential: ±exp(−d/w); power: (1 − d/w)^a within w of the edge (Boyaci et al. 2007, "
         "stimupy)"},
        {"amplitude", "4", "ΔL* per unit of λ at the edge (without edges)"},
        {"exponent", "2.75", "the power profile's exponent a"},
        {"edges", "",
         "power profile: the L* at the edge on the dark (left) and bright (right) side, with "
         "plateau"},
        {"plateau", "", "power profile: the L* the ramps start from, with edges"},
        {"sigma_px", "", "width w in pixels (image mode)"},
        {"sigma", "", "width w in world units (surface mode)"},
        {"edge_point", "0,0,0", "a point on the 3D edge (surface mode)"},
        {"edge_direction", "1,0,0", "the edge's direction (surface mode)"},
        {"bright_normal", "0,0,1", "normals within 60° of it take the bright side (surface mode)"}};
  }

  std::shared_ptr<const MethodParameters> parse(const ParameterBag& bag) const override {
    auto p = std::make_shared<CornsweetParameters>();
    p->surface = bag.choice("mode", "image", {"image", "surface"}) == "surface";
    p->profile.power = bag.choice("profile", "exponential", {"exponential", "power"}) == "power";
    p->factor = bag.number("amplitude", 4.0);
    if (!(p->factor > 0)) bag.fail("amplitude", "must be a positive ΔL*");
    p->profile.width = read_width(bag, p->surface);
    if (p->surface) {
      p->edge_point = bag.vec3("edge_point", p->edge_point);
      p->edge_direction = bag.vec3("edge_direction", p->edge_direction);
      p->bright_normal = bag.vec3("bright_normal", p->bright_normal);
    }
    p->profile.exponent = bag.number_in("exponent", 2.75, 1e-3, 100.0);
    if (p->profile.power)
      read_edge_values(bag, *p);
    else
      for (const char* key : {"exponent", "edges", "plateau"})
        if (bag.has(key)) bag.fail(key, "belongs to the power profile (profile: power)");
    bag.finish(name());
    if (glm::length(p->edge_direction) < 1e-9) bag.fail("edge_direction", "must not be zero");
    if (glm::length(p->bright_normal) < 1e-9) bag.fail("bright_normal", "must not be zero");
    return p;
  }

  RenderRequest request(const MethodParameters& parameters) const override {
    RenderRequest r;
    r.scene = parameters_as<CornsweetParameters>(parameters).surface;
    return r;
  }
  std::shared_ptr<const SurfaceStage> surface_stage(
      const SurfaceContext&, const MethodParameters& parameters) const override {
    const auto& p = parameters_as<CornsweetParameters>(parameters);
    return p.surface ? std::make_shared<SurfaceProfileStage>(p) : nullptr;
  }
  std::string label(const MethodParameters& parameters) const override {
    return name() +
           (parameters_as<CornsweetParameters>(parameters).surface ? "-surface" : "-image");
  }

  std::unique_ptr<PreparedEnhancement> prepare(const PrepareContext& context,
                                               const MethodParameters& parameters) const override {
    const auto& p = parameters_as<CornsweetParameters>(parameters);
    const View& view = *context.view;
    if (p.surface && !view.scene)
      throw InputError("cornsweet: the surface mode needs a rendered scene");
    if (p.surface && context.fields.size() != 1)
      throw std::logic_error(
          "cornsweet: the view was not rendered for these parameters (render it for a plan with "
          "them)");
    LightnessChange change;
    change.amount = p.surface ? surface_profile(view, *context.fields[0])
                              : cornsweet_image_profile(p.profile, view.width(), view.height());
    change.factor = p.factor;
    nlohmann::json record = {
        {"mode", p.surface ? "surface" : "image"},
        {"profile", p.profile.power ? "power" : "exponential"},
        {"edge_per_lambda", {p.factor * p.profile.dark, p.factor * p.profile.bright}},
        {"width", p.profile.width}};
    if (p.profile.power) record["exponent"] = p.profile.exponent;
    return std::make_unique<LightnessPrepared>(context.view, std::move(change), std::move(record),
                                               std::vector<std::pair<std::string, Image>>{},
                                               context.threads);
  }
};

}  // namespace

std::unique_ptr<const EnhancementMethod> make_cornsweet_method() {
  return std::make_unique<CornsweetMethod>();
}

}  // namespace countershade
