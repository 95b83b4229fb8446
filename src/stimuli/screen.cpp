#include "stimuli/screen.h"

#include "core/visual_angle.h"

namespace countershade {

double Screen::pixels_per_degree() const {
  return countershade::pixels_per_degree(width_mm, width_px, distance_mm);
}

Screen read_screen(const JsonObject& o) {
  Screen s;
  s.width_mm = o.number_in("width_mm", 0, 1.0, 1e5);
  s.width_px = int(o.integer_in("width_px", 0, 1, 1 << 16));
  s.distance_mm = o.number_in("distance_mm", 0, 1.0, 1e6);
  for (const char* key : {"width_mm", "width_px", "distance_mm"})
    if (!o.has(key))
      o.fail(
          key,
          "required: the screen is given by its width in mm and pixels and the viewing distance");
  o.finish();
  return s;
}

}  // namespace countershade
