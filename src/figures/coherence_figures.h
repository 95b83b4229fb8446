#pragma once
// The figures of a set whose experiment measures perspective coherence: every stimulus's RMS
// change of its enhancement under the camera dolly, as a table, and per scene a plot of it against
// λ with one line per condition and the plain render's own reprojection error dashed.

#include <filesystem>

#include "formats/manifest.h"
#include "stimuli/experiment.h"

namespace countershade {

// DIR/coherence.csv and DIR/coherence-SCENE.svg; nothing when no entry has a coherence figure.
void write_coherence_figures(const Experiment& experiment, const std::filesystem::path& dir,
                             const Manifest& manifest);

}  // namespace countershade
