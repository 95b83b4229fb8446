#pragma once
// 3D unsharp masking over mesh surfaces (Ritschel et al. 2008), as defined in docs/methods:
// per-vertex lightness L* of the display-referred outgoing radiance, smoothed by n uniform
// Laplacian steps (n from σ and each component's mean edge length), contrast per pixel against
// the barycentrically interpolated smooth signal, adaptive gain λ·w·√(1+Var), lightness-only
// composition.

#include <vector>

#include "enhance/method.h"
#include "mesh/adjacency.h"

namespace countershade {

// The per-vertex quantities of one object for one σ, exposed for tests and tools.
struct SurfaceContrast {
  std::vector<double> lightness;         // L* of the display-referred vertex signal S
  std::vector<double> smooth_lightness;  // L*_σ
  std::vector<double> gain_factor;       // w·√(1+Var) (or w with adaptation off)
  std::vector<int> iterations;           // per connected component
  Components components;
};

// Lightness of a linear radiance under the display's exposure, encoding and `bits` quantisation
// (exactly what the stimulus shows), in CIELAB L*.
double display_lightness(const glm::dvec3& radiance, const Display& display, int bits);

// σ in world units from the options (absolute, or a fraction of the scene diagonal); 0 when the
// options give explicit iterations instead.
double resolve_sigma(const MethodOptions& options, const Scene& scene);

// Steps 3 and 5 of the method on any per-vertex lightness: smoothing per component, and the gain
// factor w·√(1+Var) (importance may be empty: w = 1).
SurfaceContrast surface_contrast(const VertexAdjacency& adjacency, const std::vector<glm::vec3>& positions,
                                 std::vector<double> lightness, const std::vector<float>& importance,
                                 const MethodOptions& options, double sigma_world);

// The same for a rendered object: lightness of its display-referred vertex radiance, quantised
// like the view's pixels (`bits`) so a uniform surface has C = 0 exactly.
SurfaceContrast surface_contrast(const Object& object, const std::vector<glm::vec3>& vertex_radiance,
                                 const Display& display, const MethodOptions& options, double sigma_world,
                                 int bits = 8);

class Usm3dMethod final : public EnhancementMethod {
 public:
  std::string name() const override { return "usm3d"; }
  std::string summary() const override { return "3D unsharp masking over the mesh surface (Ritschel et al. 2008)"; }
  bool needs_vertex_radiance() const override { return true; }
  void validate(const MethodOptions& options) const override;
  std::unique_ptr<PreparedEnhancement> prepare(const View& view, const MethodOptions& options) const override;
};

// Per-pixel results of preparing a view, exposed for tests: contrast C and gain factor per pixel
// (0 for background).
struct Usm3dPixels {
  std::vector<double> contrast, gain_factor;
};
Usm3dPixels usm3d_pixels(const View& view, const std::vector<SurfaceContrast>& objects);

}  // namespace countershade
