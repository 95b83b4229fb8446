#pragma once
// A method's mask (PreparedEnhancement::mask) as a file of a stimulus set's sequences, so that
// its flicker is measured from the files as written, like the stimuli's: a 16-bit grey PNG whose
// code values map [0,1] linearly onto [−100, 200] L*, a step of 0.0046 L* (the masks of usm3d and
// usm2d lie in [0,100]; depth-usm's 100·ΔD in [−100, 100]).

#include <filesystem>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "stimuli/experiment.h"
#include "stimuli/set_layout.h"

namespace countershade {

// The mask of a sequence's condition at its frame: SCENE/LABEL/sigma-S/mask/frame-NNNN.png.
std::string mask_path(const Experiment& e, const SetUnit& unit);

// Writes the mask to dir/rel and returns its manifest record {"file", "sha256"}.
nlohmann::json write_mask(const std::filesystem::path& dir, const std::string& rel,
                          std::span<const float> mask, int width, int height);

// The mask of a file written by write_mask, in L*.
std::vector<float> read_mask(const std::filesystem::path& file);

}  // namespace countershade
