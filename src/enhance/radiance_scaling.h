#pragma once
// Radiance scaling's pieces (the method lives in radiance_scaling.cpp), for tests.

#include "core/image.h"
#include "enhance/view.h"

namespace countershade {

// σ(κ, δ) for enhancement α: the factor on a light sample's reflected radiance; σ(0, δ) = 1.
double radiance_scale(double kappa, double delta, double alpha, double gamma);
// The view's curvature κ per pixel, positive on convex parts, 0 on background pixels.
Image view_curvature(const View& view, double tau);

}  // namespace countershade
