#pragma once
// Stimuli as the app's textures take them: 8-bit RGBA, checked against the manifest's size.

#include <cstdint>
#include <vector>

#include "adjust/study.h"

namespace countershade::adjust {

// Decodes an 8-bit stimulus into RGBA; the size must be the manifest's. Throws InputError.
std::vector<uint8_t> decode_rgba(const StimulusImage& image);

}  // namespace countershade::adjust
