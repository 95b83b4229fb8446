#include "enhance/usm3d.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/image.h"
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

double resolve_sigma(const MethodOptions& options, const Scene& scene) {
  if (options.sigma) return *options.sigma;
  if (options.sigma_fraction) return *options.sigma_fraction * double(scene.bounds().diagonal());
  return 0.0;
}

SurfaceContrast surface_contrast(const VertexAdjacency& adjacency, const std::vector<glm::vec3>& positions,
                                 std::vector<double> lightness, const std::vector<float>& importance,
                                 const MethodOptions& options, double sigma_world) {
  const size_t n = lightness.size();
  SurfaceContrast out;
  out.lightness = std::move(lightness);
  out.components = connected_components(adjacency);
  if (options.iterations) {
    out.iterations.assign(out.components.count, *options.iterations);
  } else {
    std::vector<double> edge = component_mean_edge_length(positions, adjacency, out.components);
    for (double h : edge) out.iterations.push_back(iterations_for_sigma(sigma_world, h));
  }
  out.smooth_lightness = out.lightness;
  laplacian_smooth(adjacency, out.components.label, out.iterations, out.smooth_lightness);

  std::vector<double> variance(n, 0.0);
  if (options.adapt) {
    std::vector<double> unit(n);
    for (size_t v = 0; v < n; ++v) unit[v] = out.lightness[v] / 100.0;  // Var in L*/100 units
    variance = one_ring_variance(adjacency, unit);
  }
  out.gain_factor.resize(n);
  for (size_t v = 0; v < n; ++v) {
    double w = importance.empty() ? 1.0 : double(importance[v]);
    out.gain_factor[v] = w * std::sqrt(1.0 + variance[v]);
  }
  return out;
}

SurfaceContrast surface_contrast(const Object& object, const std::vector<glm::vec3>& vertex_radiance,
                                 const Display& display, const MethodOptions& options, double sigma_world,
                                 int bits) {
  const TriangleMesh& mesh = object.mesh;
  std::vector<double> lightness(mesh.vertex_count());
  for (size_t v = 0; v < lightness.size(); ++v) lightness[v] = display_lightness(vertex_radiance[v], display, bits);
  return surface_contrast(object.adjacency, mesh.positions,
                          std::move(lightness), object.importance, options, sigma_world);
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

void Usm3dMethod::validate(const MethodOptions& o) const {
  int given = int(o.sigma.has_value()) + int(o.sigma_fraction.has_value()) + int(o.iterations.has_value());
  if (given != 1) throw InputError("usm3d: give exactly one of --sigma, --sigma-fraction or --iterations");
  if (o.sigma && !(*o.sigma > 0 && std::isfinite(*o.sigma)))
    throw InputError("usm3d: --sigma must be a positive world-space length");
  if (o.sigma_fraction && !(*o.sigma_fraction > 0 && *o.sigma_fraction <= 1))
    throw InputError("usm3d: --sigma-fraction must be in (0, 1]");
  if (o.iterations && *o.iterations < 1) throw InputError("usm3d: --iterations must be at least 1");
}

namespace {

class Usm3dPrepared final : public PreparedEnhancement {
 public:
  Usm3dPrepared(const View& view, Usm3dPixels pixels, nlohmann::json parameters)
      : view_(view), pixels_(std::move(pixels)), parameters_(std::move(parameters)) {}

  Composed compose(double lambda) const override {
    std::vector<double> delta(pixels_.contrast.size());
    for (size_t i = 0; i < delta.size(); ++i) delta[i] = lambda * pixels_.gain_factor[i] * pixels_.contrast[i];
    return compose_lightness(view_.display, view_.lab, delta, view_.encoding);
  }
  nlohmann::json parameters() const override { return parameters_; }

 private:
  const View& view_;
  Usm3dPixels pixels_;
  nlohmann::json parameters_;
};

}  // namespace

std::unique_ptr<PreparedEnhancement> Usm3dMethod::prepare(const View& view, const MethodOptions& options) const {
  validate(options);
  if (!view.scene) throw InputError("usm3d: needs a rendered scene (it works on mesh surfaces)");
  const Scene& scene = *view.scene;
  if (view.render.vertex_radiance.size() != scene.objects.size())
    throw std::logic_error("usm3d: the view was rendered without vertex radiance");
  double sigma = resolve_sigma(options, scene);
  std::vector<SurfaceContrast> objects;
  nlohmann::json iterations = nlohmann::json::object();
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    objects.push_back(
        surface_contrast(scene.objects[o], view.render.vertex_radiance[o], scene.display, options, sigma, view.bits));
    // The iteration count of the object's largest component (components of one object usually
    // share a tessellation, so their counts agree).
    std::vector<size_t> size(objects.back().components.count, 0);
    for (uint32_t label : objects.back().components.label) ++size[label];
    size_t largest = size_t(std::max_element(size.begin(), size.end()) - size.begin());
    iterations[scene.objects[o].name] = objects.back().iterations[largest];
  }
  nlohmann::json parameters = {{"sigma", sigma}, {"iterations", iterations}, {"adapt", options.adapt}};
  return std::make_unique<Usm3dPrepared>(view, usm3d_pixels(view, objects), std::move(parameters));
}

}  // namespace countershade
