#pragma once
// A perceptually ordered false-colour scale (viridis: dark blue, through teal and green, to
// yellow) for maps of values in [0, 1].

#include "core/image.h"

namespace countershade {

// Display code values (sRGB, each in [0, 1]) for t in [0, 1]; t outside is clamped, NaN is black.
void false_colour(double t, float* rgb);

// A one-channel image of values in [0, 1] as a three-channel display image.
Image false_colour_image(const Image& values);

}  // namespace countershade
