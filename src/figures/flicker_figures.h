#pragma once
// The figures of a set with sequences: every frame's flicker as a table, and per scene and λ a
// plot of flicker against frame with one line per condition and the plain render's own
// reprojection error dashed, and one of the stable flicker.

#include <filesystem>

#include "formats/manifest.h"
#include "stimuli/experiment.h"

namespace countershade {

// DIR/flicker.csv, and DIR/flicker-SCENE-lambda-Λ.svg and DIR/flicker-stable-SCENE-lambda-Λ.svg
// for every λ ≠ 0 of the grid; nothing when no entry has a flicker figure.
void write_flicker_figures(const Experiment& experiment, const std::filesystem::path& dir,
                           const Manifest& manifest);

}  // namespace countershade
