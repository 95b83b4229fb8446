#pragma once
// Whether a browser showed a stimulus pixel for pixel: its 8-bit codes against a screenshot's.

#include <cmath>

#include "core/image.h"

namespace countershade::testing {

// How many of the stimulus's RGB codes differ from the screenshot's, the stimulus placed with its
// top-left at device pixel (x0, y0).
inline long differing_codes(const Image& stimulus, const Image& screen, int x0, int y0) {
  long differing = 0;
  for (int y = 0; y < stimulus.height; ++y)
    for (int x = 0; x < stimulus.width; ++x)
      for (int c = 0; c < 3; ++c)
        differing += std::lround(stimulus.at(x, y, c) * 255) !=
                     std::lround(screen.at(x0 + x, y0 + y, c) * 255);
  return differing;
}

}  // namespace countershade::testing
