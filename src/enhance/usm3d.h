#pragma once
// 3D unsharp masking over mesh surfaces (Ritschel et al. 2008), as defined in docs/methods:
// per-vertex lightness L* of the display-referred outgoing radiance, smoothed by n uniform
// Laplacian steps (n from σ and each component's mean edge length), contrast per pixel against
// the barycentrically interpolated smooth signal, adaptive gain λ·w·√(1+Var), lightness-only
// composition. The method itself lives in usm3d.cpp; these are its per-vertex steps, which
// `mesh-usm` and the tests use too.

#include <optional>
#include <vector>

#include "enhance/method.h"
#include "mesh/smoothing.h"
#include "mesh/surface_graph.h"

namespace countershade {

// How far to smooth: σ in world units, or an explicit iteration count; and whether the gain adapts.
struct SmoothingWidth {
  std::optional<double> sigma;    // world units
  std::optional<int> iterations;  // instead of σ
  bool adapt = true;              // gain √(1 + Var)
  SmoothingScheme scheme = SmoothingScheme::chebyshev;
};

// The per-vertex quantities of one object for one σ.
struct SurfaceContrast {
  std::vector<double> lightness;         // L* of the display-referred vertex signal S
  std::vector<double> smooth_lightness;  // L*_σ
  std::vector<double> gain_factor;       // w·√(1+Var) (or w with adaptation off)
  std::vector<int> iterations;           // per connected component
  Components components;                 // of the surface's points
};

// Steps 3 and 5 of the method on any per-vertex lightness: smoothing over the welded surface per
// connected component, and the gain factor w·√(1+Var) (importance may be empty: w = 1). Vertices
// at one point of the surface (a seam) share its values.
SurfaceContrast surface_contrast(const SurfaceGraph& surface, std::vector<double> lightness,
                                 const std::vector<float>& importance, const SmoothingWidth& width,
                                 int threads = 0);

// The same for a rendered object, from the display lightness of its vertex radiance.
SurfaceContrast surface_contrast(const Object& object,
                                 const std::vector<glm::vec3>& vertex_radiance,
                                 const Display& display, const SmoothingWidth& width,
                                 int threads = 0);

}  // namespace countershade
