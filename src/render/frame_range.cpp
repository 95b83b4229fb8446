#include "render/frame_range.h"

#include <sstream>

#include "core/error.h"

namespace countershade {

std::pair<int, int> frame_range(const std::string& text, const Scene& scene, int min_span,
                                const std::string& where) {
  if (!scene.animation) throw InputError(where + ": " + scene.file.string() + " has no animation");
  const int count = scene.animation->frame_count();
  int a = 0, b = 0;
  char colon = 0;
  std::istringstream in(text.empty() || text == "all" ? "0:" + std::to_string(count - 1) : text);
  if (!(in >> a >> colon >> b) || colon != ':' || !(in >> std::ws).eof() || a < 0 ||
      b < a + min_span || b >= count)
    throw InputError(where + ": expected A:B with 0 ≤ A " + std::string(min_span > 0 ? "<" : "≤") +
                     " B < " + std::to_string(count) + " (the animation's frames), got '" + text +
                     "'");
  return {a, b};
}

}  // namespace countershade
