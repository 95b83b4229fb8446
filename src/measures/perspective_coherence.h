#pragma once
// Perspective coherence (docs/enhancement-methods.md, "Perspective coherence"): the same view
// rendered twice, the second time with the camera moved a little towards its target (a dolly).
// The second frame is reprojected into the first through the depth buffer and the two cameras;
// the metric is the RMS difference of the enhancement layer (enhanced L* − plain L*) over the
// surface pixels seen in both frames. An enhancement that stays attached to the surface keeps it
// near the plain render's own reprojection error (the same RMS of plain L*).

#include <cstddef>
#include <functional>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

#include "core/image.h"
#include "enhance/view.h"
#include "render/camera.h"

namespace countershade {

// The camera moved towards its target by `fraction` of the eye–target distance.
Camera dollied(const Camera& camera, double fraction);

// L* of a stimulus minus L* of the view's own (plain) image, per pixel.
std::vector<float> enhancement_layer(const View& view, const Image& display);

struct Reprojection {
  double rms = 0;     // L*
  size_t pixels = 0;  // pixels of the first frame that entered the RMS
};

// `carry` maps a world point of object `object` in the first frame to where that surface point
// is in the moved frame (default: it stays; moving objects: their motion between the frames).
using CarryPoint = std::function<glm::dvec3(const glm::dvec3& point, int object)>;

// The carry between frames `from` and `to` of `base`'s animation: each object's path.
CarryPoint carry_between_frames(const Scene& base, int from, int to);

// RMS of first_values(x) − moved_values(x′) over the pixels x of `first` (with all 8 neighbours on
// a surface) whose surface point lands at x′ in `moved` where the moved frame sees that same
// point: its four nearest pixels are surface pixels whose bilinear 1/depth matches the point's
// within 1 %. moved_values is interpolated bicubically there; `carry` moves the point first.
// With `differences`, also |first_values(x) − moved_values(x′)| per pixel of the first frame
// (NaN where x did not count).
Reprojection reprojection_rms(const View& first, std::span<const float> first_values,
                              const View& moved, std::span<const float> moved_values,
                              const CarryPoint& carry = {},
                              std::vector<float>* differences = nullptr);

// The tolerance of a set's stable figures (flicker and coherence): the pixels whose plain L*
// reprojects within it count.
inline constexpr double kStableTolerance = 0.1;

// The RMS of `differences` (per pixel, NaN where a pixel did not count, as reprojection_rms writes
// them) over the pixels whose `plain_differences` are at most `tolerance`: where the plain render
// itself reprojects well, so that neither a change of the scene (a moving shadow) nor what the
// resampling cannot carry enters. 0 over no pixels.
Reprojection rms_where_stable(const std::vector<float>& differences,
                              const std::vector<float>& plain_differences, double tolerance);

}  // namespace countershade
