#include "enhance/usm3d.h"

#include <algorithm>
#include <cmath>

#include "core/color.h"
#include "core/error.h"
#include "core/image.h"
#include "core/parallel.h"
#include "core/random.h"
#include "enhance/lightness.h"
#include "enhance/stimulus_noise.h"
#include "mesh/smoothing.h"
#include "render/shading.h"

namespace countershade {

namespace {

// The smoothing iterations of every connected component.
std::vector<int> component_iterations(const SurfaceGraph& surface, const SmoothingWidth& width) {
  if (width.iterations) return std::vector<int>(surface.components.count, *width.iterations);
  std::vector<int> iterations;
  for (double h : surface.mean_edge_length)
    iterations.push_back(iterations_for_sigma(width.sigma.value_or(0.0), h));
  return iterations;
}

}  // namespace

SurfaceContrast surface_contrast(const SurfaceGraph& surface, std::vector<double> lightness,
                                 const std::vector<float>& importance, const SmoothingWidth& width,
                                 int threads) {
  const VertexAdjacency& adjacency = surface.adjacency;
  const size_t n = surface.point_count();
  SurfaceContrast out;
  out.components = surface.components;
  out.iterations = component_iterations(surface, width);
  const std::vector<double> point_lightness = surface.to_points(lightness);
  std::vector<double> smooth = point_lightness;
  smooth_over_rings(adjacency, out.components.label, out.iterations, smooth, width.scheme, threads);

  std::vector<double> variance(n, 0.0);
  if (width.adapt) {
    std::vector<double> unit(n);
    for (size_t p = 0; p < n; ++p) unit[p] = point_lightness[p] / 100.0;  // Var in L*/100 units
    variance = one_ring_variance(adjacency, unit, threads);
  }
  std::vector<double> weight(importance.begin(), importance.end());
  if (!weight.empty()) weight = surface.to_points(weight);
  std::vector<double> gain(n);
  parallel_ranges(
      n, threads,
      [&](size_t begin, size_t end) {
        for (size_t p = begin; p < end; ++p)
          gain[p] = (weight.empty() ? 1.0 : weight[p]) * std::sqrt(1.0 + variance[p]);
      },
      4096);
  out.lightness = std::move(lightness);
  out.smooth_lightness = surface.to_vertices(smooth);
  out.gain_factor = surface.to_vertices(gain);
  return out;
}

SurfaceContrast surface_contrast(const Object& object,
                                 const std::vector<glm::vec3>& vertex_radiance,
                                 const Display& display, const SmoothingWidth& width, int threads) {
  std::vector<double> lightness(object.mesh.vertex_count());
  const Exposure exposure = display.exposure();
  parallel_ranges(
      lightness.size(), threads,
      [&](size_t begin, size_t end) {
        for (size_t v = begin; v < end; ++v)
          lightness[v] = display_lightness(vertex_radiance[v], exposure);
      },
      4096);
  return surface_contrast(object.surface, std::move(lightness), object.importance, width, threads);
}

namespace {

struct Usm3dParameters final : MethodParameters {
  std::optional<double> sigma, sigma_fraction;  // world units; fraction of the scene diagonal
  std::optional<int> iterations;
  bool adapt = true;
  int ring_samples = 3;
  std::optional<double> refine;  // split mesh edges longer than this first
  SmoothingScheme scheme = SmoothingScheme::chebyshev;
};

// σ in world units (absolute, or a fraction of the scene diagonal); 0 with explicit iterations.
double resolve_sigma(const Usm3dParameters& p, const Scene& scene) {
  if (p.sigma) return *p.sigma;
  if (p.sigma_fraction) return *p.sigma_fraction * double(scene.bounds().diagonal());
  return 0.0;
}

// The component with the most points.
size_t largest_component(const Components& components) {
  std::vector<size_t> size(components.count, 0);
  for (uint32_t label : components.label) ++size[label];
  return size_t(std::max_element(size.begin(), size.end()) - size.begin());
}

// The iteration count of an object's largest component (components of one object usually share
// a tessellation, so their counts agree).
int largest_component_iterations(const SurfaceContrast& sc) {
  return sc.iterations[largest_component(sc.components)];
}

// The standard error of the smoothed signal at every vertex, from the signal's own errors: the
// smoothing is linear, so it is estimated by smoothing a few random-sign copies of the errors
// and taking their mean square (each vertex's estimate is rough; over pixels it is accurate).
std::vector<float> smoothed_noise(const Object& object, const SurfaceContrast& sc,
                                  const std::vector<float>& noise, SmoothingScheme scheme,
                                  int threads) {
  constexpr int kProbes = 4;  // one per component of a dvec4: smoothed side by side
  const SurfaceGraph& surface = object.surface;
  const std::vector<double> sigma =
      surface.to_points(std::vector<double>(noise.begin(), noise.end()));
  std::vector<glm::dvec4> z(sigma.size());
  parallel_ranges(
      z.size(), threads,
      [&](size_t begin, size_t end) {
        for (size_t p = begin; p < end; ++p) {
          if (sigma[p] == 0)
            continue;  // a point without error (as unshaded ones are) adds 0 whatever its sign
          for (int probe = 0; probe < kProbes; ++probe)
            z[p][probe] = (mix64(hash_combine(uint64_t(probe), p)) & 1 ? 1.0 : -1.0) * sigma[p];
        }
      },
      4096);
  smooth_over_rings(surface.adjacency, sc.components.label, sc.iterations, z, scheme, threads);
  std::vector<double> sum(sigma.size(), 0.0);
  parallel_ranges(
      z.size(), threads,
      [&](size_t begin, size_t end) {
        for (size_t p = begin; p < end; ++p) {
          for (int probe = 0; probe < kProbes; ++probe)
            sum[p] += z[p][probe] * z[p][probe] / kProbes;
          sum[p] = std::sqrt(sum[p]);
        }
      },
      4096);
  const std::vector<double> per_vertex = surface.to_vertices(sum);
  return std::vector<float>(per_vertex.begin(), per_vertex.end());
}

// One object's smoothed signal, for the front and (where the camera sees it) the back.
struct ObjectSurface {
  SurfaceContrast side[2];
  bool has_back = false;
  std::vector<float> smooth_noise[2];  // per vertex, L*
  const SurfaceContrast& of(bool back) const { return side[back && has_back]; }
  const std::vector<float>& noise_of(bool back) const { return smooth_noise[back && has_back]; }
};

// What the stage computed from the vertex signal; shared by the stage, its fields and the
// prepared method.
struct Usm3dSurface {
  const Scene* scene = nullptr;
  std::vector<ObjectSurface> objects;
  double sigma = 0;
  nlohmann::json iterations = nlohmann::json::object();

  // A per-vertex quantity of the side a point is seen from, interpolated at its barycentrics.
  template <class Get>
  double interpolate(const SurfacePoint& point, bool back, Get get) const {
    return interpolate(point.object, point.triangle, point.b1, point.b2, back, get);
  }
  template <class Get>
  double interpolate(unsigned o, unsigned triangle, double b1, double b2, bool back,
                     Get get) const {
    const glm::uvec3& t = scene->objects[o].mesh.triangles[triangle];
    const ObjectSurface& object = objects[o];
    const double b0 = 1.0 - b1 - b2;
    return b0 * get(object, back, t.x) + b1 * get(object, back, t.y) + b2 * get(object, back, t.z);
  }
};

// The luminance whose L* is the smoothed signal's, at a sample's surface point.
class SmoothLuminance final : public SampleField {
 public:
  explicit SmoothLuminance(std::shared_ptr<const Usm3dSurface> s) : s_(std::move(s)) {}
  double value(const SampleHit& hit) const override {
    const double L =
        s_->interpolate(hit.point, hit.back, [](const ObjectSurface& o, bool back, uint32_t v) {
          return o.of(back).smooth_lightness[v];
        });
    return luminance_of_lightness(L);
  }

 private:
  std::shared_ptr<const Usm3dSurface> s_;
};

// The gain factor w·√(1+Var) at a sample's surface point.
class GainFactor final : public SampleField {
 public:
  explicit GainFactor(std::shared_ptr<const Usm3dSurface> s) : s_(std::move(s)) {}
  double value(const SampleHit& hit) const override {
    return s_->interpolate(hit.point, hit.back, [](const ObjectSurface& o, bool back, uint32_t v) {
      return o.of(back).gain_factor[v];
    });
  }

 private:
  std::shared_ptr<const Usm3dSurface> s_;
};

class Usm3dStage final : public SurfaceStage {
 public:
  explicit Usm3dStage(std::shared_ptr<const Usm3dSurface> surface) : surface_(std::move(surface)) {}
  SampleFields fields() const override {
    return {std::make_shared<SmoothLuminance>(surface_), std::make_shared<GainFactor>(surface_)};
  }
  const std::shared_ptr<const Usm3dSurface>& surface() const { return surface_; }

 private:
  std::shared_ptr<const Usm3dSurface> surface_;
};

std::shared_ptr<const Usm3dSurface> smooth_surfaces(const Scene& scene, const VertexSignal& signal,
                                                    const Usm3dParameters& p, int threads) {
  require_surface_graphs(scene, "usm3d");
  auto out = std::make_shared<Usm3dSurface>();
  out->scene = &scene;
  out->sigma = resolve_sigma(p, scene);
  const SmoothingWidth width{out->sigma, p.iterations, p.adapt, p.scheme};
  out->objects.resize(scene.objects.size());
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    ObjectSurface& surface = out->objects[o];
    surface.has_back = !signal.back[o].empty();
    for (int side = 0; side < (surface.has_back ? 2 : 1); ++side) {
      const auto& radiance = side ? signal.back[o] : signal.front[o];
      surface.side[side] =
          surface_contrast(scene.objects[o], radiance, scene.display, width, threads);
      surface.smooth_noise[side] =
          smoothed_noise(scene.objects[o], surface.side[side],
                         side ? signal.back_noise[o] : signal.front_noise[o], p.scheme, threads);
    }
    out->iterations[scene.objects[o].name] = largest_component_iterations(surface.side[0]);
  }
  return out;
}

// The per-pixel contrast, coverage-correct: C = L*(Y) − L*(Y − D). Y is the pixel's display
// luminance taken per surface: over each surface it sees (and the background), the share of its
// samples there times the display luminance of their mean radiance. D is the same sum over the
// surfaces of that luminance less the mean smoothed signal of the surface's samples. So Y − D is
// the pixel with every surface replaced by its smooth signal: a surface of uniform radiance has
// D = 0 and C = 0 at every pixel, its silhouette included, and two objects never exchange contrast
// at a shared edge. The clamp at white applies to each surface's mean radiance, as it does to the
// reference pixel and to each vertex's signal, so C does not depend on how unevenly the samples
// spread the light (render/surface_sums.h).
double coverage_contrast(double luminance, double surface_luminance, double smooth_luminance) {
  const double d = surface_luminance - smooth_luminance;
  return cielab_lightness(luminance) - cielab_lightness(std::max(luminance - d, 0.0));
}

// The change per unit λ of one replicate, g·C, for the pixel pass's noise estimate; g is the mean
// gain factor over the surface samples.
class Usm3dChange final : public ChangePerLambda {
 public:
  double value(const PixelMeans& m) const override {
    if (!(m.coverage > 0)) return 0.0;
    return m.fields[1] / m.coverage *
           coverage_contrast(m.luminance, m.surface_luminance, m.fields[0]);
  }
};

struct CoverageContrast {
  PixelDoubles contrast;
  std::vector<double> gain;
  std::vector<float> smooth_noise;  // per unit λ: |g|·coverage·(the smoothed signal's L* error)
};

// The mask M = L*(Y − D), so that C = L*(Y) − M; L*(Y) off the surface. Made only when a set
// keeps masks.
std::vector<float> contrast_mask(const RenderResult& r, const PixelDoubles& contrast, int threads) {
  std::vector<float> mask(contrast.size());
  parallel_ranges(
      mask.size(), threads,
      [&](size_t begin, size_t end) {
        for (size_t p = begin; p < end; ++p)
          mask[p] = float(cielab_lightness(r.luminance[p])) - float(contrast[p]);
      },
      4096);
  return mask;
}

CoverageContrast coverage_contrast(const View& view, const Usm3dSurface& surface,
                                   const std::vector<const std::vector<float>*>& fields,
                                   int threads) {
  const RenderResult& r = view.render;
  const GBuffer& g = r.gbuffer;
  const size_t n = r.luminance.size();
  CoverageContrast out;
  out.contrast.assign(n, 0.0);
  out.gain.assign(n, 0.0);
  out.smooth_noise.assign(n, 0.0f);
  const std::vector<float>& smooth_luminance = *fields[0];
  const std::vector<float>& gain = *fields[1];
  parallel_ranges(
      n, threads,
      [&](size_t begin, size_t end) {
        for (size_t p = begin; p < end; ++p) {
          if (!(r.coverage[p] > 0)) continue;
          out.contrast[p] =
              coverage_contrast(r.luminance[p], r.surface_luminance[p], smooth_luminance[p]);
          out.gain[p] = double(gain[p]) / double(r.coverage[p]);
          if (g.object[p] < 0) continue;
          // At the pixel centre's point: its barycentrics are all the interpolation reads.
          const double error = surface.interpolate(
              unsigned(g.object[p]), unsigned(g.triangle[p]), double(g.barycentrics[p].x),
              double(g.barycentrics[p].y), g.back[p] != 0,
              [](const ObjectSurface& o, bool back, uint32_t v) {
                return double(o.noise_of(back)[v]);
              });
          out.smooth_noise[p] = float(std::abs(out.gain[p]) * r.coverage[p] * error);
        }
      },
      4096);
  return out;
}

class Usm3dMethod final : public EnhancementMethod {
 public:
  std::string name() const override { return "usm3d"; }
  std::string summary() const override {
    return "3D unsharp masking over the mesh surface (Ritschel et al. 2008)";
  }
  MethodAxes axes() const override {
    return {"gain g = λ·w·√(1+Var) on the surface contrast C = L*_pixel − L*_σ",
            {{"sigma", "world units", "smoothing width σ on the surface"},
             {"sigma_fraction", "of the scene diagonal",
              "σ as a fraction of the scene's bounding-box diagonal"},
             {"iterations", "iterations", "an explicit number of smoothing iterations"}}};
  }
  std::vector<ParameterDoc> parameter_docs() const override {
    return {{"sigma", "", "smoothing width σ in world units"},
            {"sigma_fraction", "", "σ as a fraction of the scene's bounding-box diagonal"},
            {"iterations", "", "explicit number of smoothing iterations instead of σ"},
            {"adapt", "true", "adaptive gain √(1+Var) (--no-adapt: constant gain λ·w)"},
            {"ring_samples", "3",
             "anti-aliasing samples per incident triangle for the vertex signal (0 = off)"},
            {"refine", "", "split mesh edges longer than this world length before rendering"},
            {"smoothing", "chebyshev",
             "chebyshev (the n 1-ring steps in O(√n) products, within 1e-7 of the signal's range) "
             "| iterate (one product "
             "per step)"}};
  }

  std::shared_ptr<const MethodParameters> parse(const ParameterBag& bag) const override {
    auto p = std::make_shared<Usm3dParameters>();
    p->sigma = bag.optional_number("sigma");
    p->sigma_fraction = bag.optional_number("sigma_fraction");
    if (auto n = bag.optional_integer("iterations", 1, 1000000)) p->iterations = int(*n);
    p->adapt = bag.boolean("adapt", true);
    p->ring_samples = int(bag.integer_in("ring_samples", 3, 0, 64));
    p->refine = bag.optional_number("refine");
    if (bag.choice("smoothing", "chebyshev", {"chebyshev", "iterate"}) == "iterate")
      p->scheme = SmoothingScheme::iterate;
    bag.finish(name());
    const int given = int(p->sigma.has_value()) + int(p->sigma_fraction.has_value()) +
                      int(p->iterations.has_value());
    if (given != 1)
      throw_input_error(name(), "give exactly one of " + bag.where("sigma") + ", " +
                                    bag.where("sigma_fraction") + " or " + bag.where("iterations"));
    if (p->sigma && !(*p->sigma > 0)) bag.fail("sigma", "must be a positive world-space length");
    if (p->sigma_fraction && !(*p->sigma_fraction > 0 && *p->sigma_fraction <= 1))
      bag.fail("sigma_fraction", "must be in (0, 1]");
    if (p->refine && !(*p->refine > 0)) bag.fail("refine", "must be a positive world-space length");
    return p;
  }

  RenderRequest request(const MethodParameters& parameters) const override {
    const auto& p = parameters_as<Usm3dParameters>(parameters);
    RenderRequest r;
    r.scene = true;
    r.vertex_radiance = true;
    r.ring_samples = p.ring_samples;
    r.refine_edge_length = p.refine;
    return r;
  }

  std::shared_ptr<const SurfaceStage> surface_stage(
      const SurfaceContext& context, const MethodParameters& parameters) const override {
    if (context.render.vertices.front.size() != context.scene.objects.size())
      throw std::logic_error("usm3d: the view was rendered without vertex radiance");
    return std::make_shared<Usm3dStage>(smooth_surfaces(context.scene, context.render.vertices,
                                                        parameters_as<Usm3dParameters>(parameters),
                                                        context.threads));
  }

  std::shared_ptr<const ChangePerLambda> change_per_lambda(const MethodParameters&) const override {
    return std::make_shared<Usm3dChange>();
  }
  // The smoothed signal's error is the vertices' divided by √(6n) (n steps of the 1-ring mean
  // average over at least 6n vertices of valence 6, see tests/mesh/smoothing_test), then multiplied
  // by the gain λ·|w|·√(1+Var) ≤ λ·|w|·√1.25. It matters within three σ (in rings) of what the
  // camera sees.
  std::vector<VertexNeed> vertex_needs(const Scene& scene, const MethodParameters& parameters,
                                       double max_abs_lambda, double allowed) const override {
    const auto& p = parameters_as<Usm3dParameters>(parameters);
    const SmoothingWidth width{resolve_sigma(p, scene), p.iterations, p.adapt, p.scheme};
    std::vector<VertexNeed> needs;
    for (const auto& object : scene.objects) {
      double weight = object.importance.empty() ? 1.0 : 0.0;
      for (float w : object.importance) weight = std::max(weight, double(std::abs(w)));
      // The largest component's smoothing: small loose parts would make the need of the whole
      // object needlessly strict.
      const std::vector<int> iterations = component_iterations(object.surface, width);
      const int n =
          iterations.empty() ? 1 : iterations[largest_component(object.surface.components)];
      const int widest =
          iterations.empty() ? 1 : *std::max_element(iterations.begin(), iterations.end());
      const double gain = max_abs_lambda * weight * std::sqrt(1.25);
      VertexNeed need;
      need.noise = gain > 0 ? allowed * std::sqrt(6.0 * n) / gain : scene.settings.noise.target;
      need.rings = int(std::ceil(3.0 * std::sqrt(widest / 2.0))) + 1;
      // n smoothing steps (or a Chebyshev expansion of degree ≤ n) reach n rings; the gain's
      // 1-ring variance reaches one.
      need.support = std::max(widest, 1);
      needs.push_back(need);
    }
    return needs;
  }

  std::unique_ptr<PreparedEnhancement> prepare(const PrepareContext& context,
                                               const MethodParameters& parameters) const override {
    const auto& p = parameters_as<Usm3dParameters>(parameters);
    if (!context.view->scene)
      throw InputError("usm3d: needs a rendered scene (it works on mesh surfaces)");
    const auto* stage = dynamic_cast<const Usm3dStage*>(context.stage.get());
    if (!stage || context.fields.size() != 2)
      throw std::logic_error(
          "usm3d: the view was not rendered for these parameters (render it for a plan with them)");
    auto pixels = std::make_shared<const CoverageContrast>(
        coverage_contrast(*context.view, *stage->surface(), context.fields, context.threads));
    LightnessChange change;
    change.amount = pixels->contrast;
    change.gain = pixels->gain;
    nlohmann::json record = {{"sigma", stage->surface()->sigma},
                             {"iterations", stage->surface()->iterations},
                             {"adapt", p.adapt}};
    NoiseFunction noise = [view = context.view, change = context.change_noise,
                           pixels](double lambda) {
      return lambda_noise(*view, change, lambda, pixels->smooth_noise);
    };
    auto prepared = std::make_unique<LightnessPrepared>(
        context.view, std::move(change), std::move(record),
        std::vector<std::pair<std::string, Image>>{}, context.threads, std::move(noise));
    prepared->set_mask([pixels, view = context.view, threads = context.threads] {
      return contrast_mask(view->render, pixels->contrast, threads);
    });
    return prepared;
  }
};

}  // namespace

std::unique_ptr<const EnhancementMethod> make_usm3d_method() {
  return std::make_unique<Usm3dMethod>();
}

}  // namespace countershade
