#pragma once
// What enhancement methods ask of the pixel pass.
//
// Sample fields: per-sample quantities that a method needs averaged over each pixel. The pixel
// renderer evaluates a field at every sample that hits a surface and averages over all of the
// pixel's samples, background samples counting 0. A value that depends on the surface under each
// sample is then exact at anti-aliased edges, occlusion boundaries and pixels shared by two
// objects (docs/enhancement-methods.md: coverage-correct contrast).
//
// Changes per unit λ: how a method changes a pixel's L*, computed from one replicate's means.
// A stimulus is L + λ·c; comparing the two replicates of every pixel gives Var(L), Cov(L, c) and
// Var(c), hence the stimulus's sampling noise at every λ, silhouettes included (where the
// pixel's L* is noisy but its contrast is not).

#include <memory>
#include <vector>

namespace countershade {

struct SurfacePoint;

struct SampleHit {
  const SurfacePoint& point;
  bool back = false;  // the ray saw the back of the triangle (the side opposite its winding)
};

class SampleField {
 public:
  virtual ~SampleField() = default;
  virtual double value(const SampleHit& hit) const = 0;
};

using SampleFields = std::vector<std::shared_ptr<const SampleField>>;

// Means over one replicate's samples of a pixel (or over all of them).
struct PixelMeans {
  double lightness = 0;  // L* of the display luminance of the mean radiance
  // Σ over the pixel's surfaces (and background) of share × display luminance of that surface's
  // mean radiance: the clamp at white applies to each surface's mean, never to single samples.
  double luminance = 0;            // surfaces and background
  double surface_luminance = 0;    // surfaces alone
  double coverage = 0;             // share of samples that hit a surface
  const double* fields = nullptr;  // the method's own fields, in the order of its stage's fields()
};

class ChangePerLambda {
 public:
  virtual ~ChangePerLambda() = default;
  // c in L' = L + λ·c, from one replicate's means.
  virtual double value(const PixelMeans& means) const = 0;
};

// The plain gain of image-space methods: c = gain·L (usm2d's detail L − G*L passes L's noise).
class LightnessTimes final : public ChangePerLambda {
 public:
  explicit LightnessTimes(double gain) : gain_(gain) {}
  double value(const PixelMeans& means) const override { return gain_ * means.lightness; }

 private:
  double gain_;
};

// The noise of a change, per pixel, pooled over 3×3 neighbours like the pixel's own.
struct ChangeNoise {
  std::vector<float> covariance;  // Cov(L, c)
  std::vector<float> variance;    // Var(c)
};

}  // namespace countershade
