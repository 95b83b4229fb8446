#include "enhance/usm3d.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/image.h"
#include "enhance/lightness.h"
#include "mesh/smoothing.h"

namespace countershade {

double display_lightness(const glm::dvec3& radiance, const Display& display, int bits) {
  const double scale = std::exp2(display.exposure_stops);
  const float levels = float((1u << bits) - 1u);
  float code[3];
  for (int c = 0; c < 3; ++c)
    code[c] = float(quantize(float(display.encoding.encode(radiance[c] * scale)), bits)) / levels;
  return display_pixel_to_lab(code, display.encoding).L;  // the same path as the pixels
}

SurfaceContrast surface_contrast(const SurfaceGraph& surface, const std::vector<glm::vec3>& positions,
                                 std::vector<double> lightness, const std::vector<float>& importance,
                                 const SmoothingWidth& width) {
  const VertexAdjacency& adjacency = surface.adjacency;
  const size_t n = surface.point_count();
  SurfaceContrast out;
  out.components = surface.components;
  if (width.iterations) {
    out.iterations.assign(out.components.count, *width.iterations);
  } else {
    std::vector<glm::vec3> points(n);
    for (size_t p = 0; p < n; ++p) points[p] = positions[surface.first_vertex[p]];
    for (double h : component_mean_edge_length(points, adjacency, out.components))
      out.iterations.push_back(iterations_for_sigma(width.sigma.value_or(0.0), h));
  }
  const std::vector<double> point_lightness = surface.to_points(lightness);
  std::vector<double> smooth = point_lightness;
  laplacian_smooth(adjacency, out.components.label, out.iterations, smooth);

  std::vector<double> variance(n, 0.0);
  if (width.adapt) {
    std::vector<double> unit(n);
    for (size_t p = 0; p < n; ++p) unit[p] = point_lightness[p] / 100.0;  // Var in L*/100 units
    variance = one_ring_variance(adjacency, unit);
  }
  std::vector<double> weight(importance.begin(), importance.end());
  if (!weight.empty()) weight = surface.to_points(weight);
  std::vector<double> gain(n);
  for (size_t p = 0; p < n; ++p) gain[p] = (weight.empty() ? 1.0 : weight[p]) * std::sqrt(1.0 + variance[p]);
  out.lightness = std::move(lightness);
  out.smooth_lightness = surface.to_vertices(smooth);
  out.gain_factor = surface.to_vertices(gain);
  return out;
}

SurfaceContrast surface_contrast(const Object& object, const std::vector<glm::vec3>& vertex_radiance,
                                 const Display& display, const SmoothingWidth& width, int bits) {
  std::vector<double> lightness(object.mesh.vertex_count());
  for (size_t v = 0; v < lightness.size(); ++v) lightness[v] = display_lightness(vertex_radiance[v], display, bits);
  return surface_contrast(object.surface, object.mesh.positions, std::move(lightness), object.importance, width);
}

Usm3dPixels usm3d_pixels(const View& view, const std::vector<SurfaceContrast>& objects) {
  const GBuffer& g = view.render.gbuffer;
  const size_t n = size_t(g.width) * g.height;
  Usm3dPixels out;
  out.contrast.assign(n, 0.0);
  out.gain_factor.assign(n, 0.0);
  for (size_t i = 0; i < n; ++i) {
    if (g.object[i] < 0) continue;
    const SurfaceContrast& sc = objects[size_t(g.object[i])];
    const glm::uvec3& tri = view.scene->objects[size_t(g.object[i])].mesh.triangles[size_t(g.triangle[i])];
    double b1 = g.barycentrics[i].x, b2 = g.barycentrics[i].y, b0 = 1.0 - b1 - b2;
    double smooth = b0 * sc.smooth_lightness[tri.x] + b1 * sc.smooth_lightness[tri.y] + b2 * sc.smooth_lightness[tri.z];
    out.contrast[i] = view.lab[i].L - smooth;
    out.gain_factor[i] = b0 * sc.gain_factor[tri.x] + b1 * sc.gain_factor[tri.y] + b2 * sc.gain_factor[tri.z];
  }
  return out;
}

namespace {

struct Usm3dParameters final : MethodParameters {
  std::optional<double> sigma, sigma_fraction;  // world units; fraction of the scene diagonal
  std::optional<int> iterations;
  bool adapt = true;
  int ring_samples = 3;
  std::optional<double> refine;  // split mesh edges longer than this first
};

// σ in world units (absolute, or a fraction of the scene diagonal); 0 with explicit iterations.
double resolve_sigma(const Usm3dParameters& p, const Scene& scene) {
  if (p.sigma) return *p.sigma;
  if (p.sigma_fraction) return *p.sigma_fraction * double(scene.bounds().diagonal());
  return 0.0;
}

// The iteration count of an object's largest component (components of one object usually share
// a tessellation, so their counts agree).
int largest_component_iterations(const SurfaceContrast& sc) {
  std::vector<size_t> size(sc.components.count, 0);
  for (uint32_t label : sc.components.label) ++size[label];
  return sc.iterations[size_t(std::max_element(size.begin(), size.end()) - size.begin())];
}

class Usm3dMethod final : public EnhancementMethod {
 public:
  std::string name() const override { return "usm3d"; }
  std::string summary() const override { return "3D unsharp masking over the mesh surface (Ritschel et al. 2008)"; }
  MethodAxes axes() const override {
    return {"gain g = λ·w·√(1+Var) on the surface contrast C = L*_pixel − L*_σ",
            {{"sigma", "world units", "smoothing width σ on the surface"},
             {"sigma_fraction", "of the scene diagonal", "σ as a fraction of the scene's bounding-box diagonal"},
             {"iterations", "iterations", "an explicit number of smoothing iterations"}}};
  }
  std::vector<ParameterDoc> parameter_docs() const override {
    return {{"sigma", "", "smoothing width σ in world units"},
            {"sigma_fraction", "", "σ as a fraction of the scene's bounding-box diagonal"},
            {"iterations", "", "explicit number of smoothing iterations instead of σ"},
            {"adapt", "true", "adaptive gain √(1+Var) (--no-adapt: constant gain λ·w)"},
            {"ring_samples", "3", "anti-aliasing samples per incident triangle for the vertex signal (0 = off)"},
            {"refine", "", "split mesh edges longer than this world length before rendering"}};
  }

  std::shared_ptr<const MethodParameters> parse(const ParameterBag& bag) const override {
    auto p = std::make_shared<Usm3dParameters>();
    p->sigma = bag.optional_number("sigma");
    p->sigma_fraction = bag.optional_number("sigma_fraction");
    if (auto n = bag.optional_integer("iterations", 1, 1000000)) p->iterations = int(*n);
    p->adapt = bag.boolean("adapt", true);
    p->ring_samples = int(bag.integer_in("ring_samples", 3, 0, 64));
    p->refine = bag.optional_number("refine");
    bag.finish(name());
    const int given = int(p->sigma.has_value()) + int(p->sigma_fraction.has_value()) + int(p->iterations.has_value());
    if (given != 1)
      throw_input_error(name(), "give exactly one of " + bag.where("sigma") + ", " + bag.where("sigma_fraction") +
                                    " or " + bag.where("iterations"));
    if (p->sigma && !(*p->sigma > 0)) bag.fail("sigma", "must be a positive world-space length");
    if (p->sigma_fraction && !(*p->sigma_fraction > 0 && *p->sigma_fraction <= 1)) bag.fail("sigma_fraction", "must be in (0, 1]");
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

  std::unique_ptr<PreparedEnhancement> prepare(const PrepareContext& context,
                                               const MethodParameters& parameters) const override {
    const auto& p = parameters_as<Usm3dParameters>(parameters);
    const View& view = *context.view;
    if (!view.scene) throw InputError("usm3d: needs a rendered scene (it works on mesh surfaces)");
    const Scene& scene = *view.scene;
    if (view.render.vertex_radiance.size() != scene.objects.size())
      throw std::logic_error("usm3d: the view was rendered without vertex radiance");
    const double sigma = resolve_sigma(p, scene);
    const SmoothingWidth width{sigma, p.iterations, p.adapt};
    std::vector<SurfaceContrast> objects;
    nlohmann::json iterations = nlohmann::json::object();
    for (size_t o = 0; o < scene.objects.size(); ++o) {
      objects.push_back(surface_contrast(scene.objects[o], view.render.vertex_radiance[o], scene.display, width, view.bits));
      iterations[scene.objects[o].name] = largest_component_iterations(objects.back());
    }
    Usm3dPixels pixels = usm3d_pixels(view, objects);
    LightnessChange change;
    change.amount = std::move(pixels.contrast);
    change.gain = std::move(pixels.gain_factor);
    nlohmann::json record = {{"sigma", sigma}, {"iterations", iterations}, {"adapt", p.adapt}};
    return std::make_unique<LightnessPrepared>(context.view, std::move(change), std::move(record),
                                               std::vector<std::pair<std::string, Image>>{}, context.threads);
  }
};

}  // namespace

std::unique_ptr<const EnhancementMethod> make_usm3d_method() { return std::make_unique<Usm3dMethod>(); }

}  // namespace countershade
