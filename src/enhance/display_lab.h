#pragma once
// Display-encoded pixels to CIELAB (docs/methods.md, "Colour"): what a view holds of its image, and
// the lightness of radiance as the display shows it.

#include <glm/vec3.hpp>
#include <vector>

#include "core/color.h"
#include "core/display.h"
#include "core/image.h"

namespace countershade {

// CIELAB per pixel; left unfilled until written (a 1920×1080 view holds 50 MB of it).
using LabPixels = std::vector<Lab, UninitializedAllocator<Lab>>;

// CIELAB of every pixel of a display-encoded image (code values in [0,1]), decoded with the
// display's own encoding. With `bits`, values that are exact codes of that depth are decoded
// through a table (the same values as DisplayEncoding::decode, without a pow per channel).
// With `lightness`, also L* as floats in one plane (View::lightness).
LabPixels display_to_lab(const Image& display, const DisplayEncoding& encoding, int bits = 0,
                         PixelVector* lightness = nullptr);
Lab display_pixel_to_lab(const float* rgb, const DisplayEncoding& encoding);
// The mean L* of a display-encoded image: the mean of display_to_lab's L*, bit for bit, without
// computing a* and b*.
double mean_display_lightness(const Image& display, const DisplayEncoding& encoding, int bits = 0);

// CIELAB L* of a linear radiance as the display shows it (Display::exposure(), per channel).
double display_lightness(const glm::dvec3& radiance, const Exposure& exposure);

}  // namespace countershade
