#pragma once
// The view-dependent curvature κ that radiance scaling and light warping read (Vergne et al.
// 2010): the divergence of the screen gradient field of the view's normals, through tanh.

#include <glm/vec3.hpp>
#include <vector>

#include "core/image.h"
#include "enhance/method.h"
#include "enhance/view.h"
#include "render/camera.h"

namespace countershade {

// The `tau` parameter of the methods that read κ (τ in pixels, default 1), and its documentation.
double read_curvature_tau(const ParameterBag& bag);
ParameterDoc curvature_tau_doc();

class ViewCurvature {
 public:
  // κ = tanh(−τ·div g) per object pixel, g = −(n_x, n_y)/n_z of the view-space normals, so that
  // κ > 0 on convex and κ < 0 on concave parts. Next to the background the derivative is
  // one-sided, so an outline pixel has the curvature of its own surface, not 0.
  ViewCurvature(const View& view, double tau);

  // κ where the world point `p` projects to, interpolated bilinearly over the object pixels among
  // the four nearest; 0 when none of them is an object pixel.
  double at(const glm::dvec3& p) const;

  // κ per pixel; background pixels are 0.
  const Image& pixels() const { return kappa_; }

 private:
  CameraRays camera_;
  Image kappa_;
  std::vector<char> object_;
};

}  // namespace countershade
