#pragma once
// Lightness-only composition shared by the enhancement methods: L' = clamp(L + Δ, 0, 100) with
// a*, b* scaled by L'/L (hue and saturation kept), back to display code values, clipped per
// channel, with a count of clipped pixels.

#include <cstddef>
#include <vector>

#include "core/color.h"
#include "core/display.h"
#include "core/image.h"

namespace countershade {

// CIELAB of every pixel of a display-encoded image (code values in [0,1]), decoded with the
// display's own encoding.
std::vector<Lab> display_to_lab(const Image& display, const DisplayEncoding& encoding);
Lab display_pixel_to_lab(const float* rgb, const DisplayEncoding& encoding);

struct Composed {
  Image display;  // code values in [0,1]
  size_t clipped_pixels = 0;  // pixels where L' left [0,100] or an RGB channel left [0,1]
};

// Applies lightness changes `delta_L` (one per pixel) to `display`. Pixels with a zero change
// keep their code values exactly, so an all-zero change reproduces the input bit for bit.
Composed compose_lightness(const Image& display, const std::vector<Lab>& lab,
                           const std::vector<double>& delta_L, const DisplayEncoding& encoding,
                           int threads = 0);

}  // namespace countershade
