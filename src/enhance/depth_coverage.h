#pragma once
// Coverage of depth-buffer unsharp masking at depth edges. The depth map holds one depth per pixel
// (its centre), so an operator applied per pixel darkens an anti-aliased silhouette pixel fully or
// not at all, and a smooth outline turns into a staircase. Where a pixel's neighbourhood has a
// depth edge, its area is sampled again (4×4 primary rays, no shading) and the operator's terms
// are averaged over those samples, each against its own depth: the outline keeps its
// anti-aliasing. Elsewhere the pixel's own ΔD is used, as before.

#include <cmath>
#include <functional>

#include "core/image.h"

namespace countershade {

struct View;

// At every pixel of a rendered view with a depth edge in its neighbourhood, replaces `darker` and
// `lighter` (min(ΔD, 0) and max(ΔD, 0) of the pixel's own ΔD = G*D − D) by their means over the
// pixel's area. `blurred` is G*D per pixel and `normalise` maps a linear eye depth to D (an
// infinite one is background). Views without a scene to trace (images read from files) are left
// as they are.
void sample_outlines(const View& view, const Image& blurred,
                     const std::function<float(float)>& normalise, Image& darker, Image& lighter,
                     int threads = 0);

// Whether a linear eye depth belongs to a surface: finite and positive (background is infinite).
inline bool valid_eye_depth(float d) { return std::isfinite(d) && d > 0.0f; }

// Whether pixel (x, y) has a depth edge in its 3×3 neighbourhood: another object, background
// against surface, or eye depths that differ by more than 5 %.
bool depth_edge_at(const View& view, int x, int y);

}  // namespace countershade
