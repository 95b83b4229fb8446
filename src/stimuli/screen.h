#pragma once
// The screen a study is shown on, as vision scientists give it (docs/display.md): its width in mm
// and in pixels and the viewing distance, hence the pixels per degree of visual angle that turn
// sizes and σ given in degrees into pixels.

#include "core/json_reader.h"

namespace countershade {

struct Screen {
  double width_mm = 0, distance_mm = 0;
  int width_px = 0;

  // The pixels that one degree spans at the screen's centre: 2·d·tan(0.5°) mm at distance d.
  double pixels_per_degree() const;
};

// "screen": {"width_mm", "width_px", "distance_mm"}; every value required and positive.
Screen read_screen(const JsonObject& o);

}  // namespace countershade
