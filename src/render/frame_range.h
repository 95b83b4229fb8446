#pragma once
// A range of an animation's frames written "A:B" (the --frames option of `render` and `flicker`,
// the "frames" key of an experiment's scene), or "" and "all" for every frame.

#include <string>
#include <utility>

#include "render/scene.h"

namespace countershade {

// Frames A … B with 0 ≤ A, A + min_span ≤ B < the animation's frame count. InputError starting
// with `where` (the option or the key path) otherwise, or when the scene has no animation.
std::pair<int, int> frame_range(const std::string& text, const Scene& scene, int min_span,
                                const std::string& where);

}  // namespace countershade
