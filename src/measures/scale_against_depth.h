#pragma once
// Scale against depth (docs/enhancement-methods.md, "Scale against depth"): on an edge probe, a
// horizontal ground whose albedo stripes run along −z at known world x, the width of an
// enhancement's halo per stripe edge and image row, against the row's eye depth. A halo attached
// to the surface shrinks as 1/depth (log-log slope −1); one of fixed screen size keeps its width
// (slope 0).

#include <cstddef>
#include <span>
#include <vector>

#include "render/camera.h"

namespace countershade {

// The 1/e width of one side of a halo: `distance` (ascending, ≥ 0, in pixels along the edge's
// normal) and the layer's magnitude there. The distance from the profile's peak to where the
// magnitude first falls below 1/e of the peak, interpolated log-linearly between samples (exact
// for an exponential fall-off). NaN where it never falls that far or the peak is 0.
double halo_width(std::span<const double> distance, std::span<const double> magnitude);

// What the probe reads of one image: its camera, and per pixel the eye depth (not finite or ≤ 0:
// background) and the enhancement layer (enhanced − plain L*).
struct ProbeImage {
  Camera camera;
  std::span<const float> depth, layer;
};

// The halo of one edge in one image row: the row's eye depth, and the mean of the widths of the
// edge's two sides (either alone where the other could not be read).
struct HaloSample {
  double edge_x = 0, depth = 0, width_px = 0;
};

// The halo widths of every `row_step`-th row at the edges x ∈ `edges_x` it crosses. Each side of
// an edge is read along the row, from the edge to halfway to the next edge (at most 64 px), and its
// distances are taken along the edge's normal in the image.
std::vector<HaloSample> halo_samples(const ProbeImage& image, std::span<const double> edges_x,
                                     int row_step = 4);

// The slope of log(width) against log(depth), by least squares with an intercept per edge, over
// the samples at least `min_width_px` wide: an edge's tilt in the image scales its widths along
// its normal by a constant, and the far rows see more of the tilted edges. NaN with fewer than 3
// samples.
struct DepthSlope {
  double slope = 0;
  size_t samples = 0;
  double depth_min = 0, depth_max = 0;
};
DepthSlope depth_slope(const std::vector<HaloSample>& samples, double min_width_px = 1.5);

}  // namespace countershade
