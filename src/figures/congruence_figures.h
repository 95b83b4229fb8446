#pragma once
// The figures of a set whose experiment scores congruence: the scores per scene and condition at
// the strongest λ as a table and a line plot (in the style of Mestres et al. 2021, Fig. 13), and
// per condition a sheet of each scene's render beside its score map (their Fig. 12).

#include <filesystem>

#include "formats/manifest.h"
#include "stimuli/experiment.h"

namespace countershade {

// DIR/congruence.csv and DIR/congruence.svg, and DIR/congruence-SCENE.svg per scene entry whose
// light directions are swept when there are several; with `sheets`,
// DIR/contact-sheets/congruence-LABEL.png.
// Nothing when the manifest lacks a score (an experiment without "congruence", or a shard).
void write_congruence_figures(const Experiment& experiment, const std::filesystem::path& dir,
                              const Manifest& manifest, bool sheets);

}  // namespace countershade
