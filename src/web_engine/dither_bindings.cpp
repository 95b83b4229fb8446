// The app's dither of 16-bit stimuli to 8 bits (src/runtime/fine_levels), for the page's WebGL2
// drawing: the GLSL is the app's own text, and the seed is hashed by the app's code, so the page
// shows the app's frame sequence.

#include <emscripten/bind.h>

#include <cstdint>
#include <string>

#include "runtime/fine_levels.h"

namespace countershade::web_engine {
namespace {

std::string fine_levels_glsl() { return runtime::kFineLevelsGlsl; }

// The dither's per-frame seed input for a session seed given as decimal text (the app's default
// dither seed is the session seed's low 32 bits).
uint32_t dither_seed_mix(const std::string& session_seed) {
  return runtime::dither_seed_mix(uint32_t(std::stoull(session_seed)));
}

}  // namespace

EMSCRIPTEN_BINDINGS(countershade_dither) {
  emscripten::function("fineLevelsGlsl", &fine_levels_glsl);
  emscripten::function("ditherSeedMix", &dither_seed_mix);
}

}  // namespace countershade::web_engine
