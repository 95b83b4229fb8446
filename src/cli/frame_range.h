#pragma once
// The --frames option of `render` and `flicker`: "A:B", frames of the scene's animation.

#include <string>
#include <utility>

#include "render/scene.h"

namespace countershade::cli {

// Frames A … B with 0 ≤ A, A + min_span ≤ B < the animation's frame count; empty text: all
// frames. InputError naming --frames otherwise, or when the scene has no animation.
std::pair<int, int> frame_range(const std::string& text, const Scene& scene, int min_span);

}  // namespace countershade::cli
