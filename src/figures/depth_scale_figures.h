#pragma once
// The figures of an edge probe's stimuli (stimuli/scale_against_depth.h): every halo width
// against its eye depth in scale-against-depth.csv, and per probe scene a log-log plot of them
// per condition at the grid's largest λ, with each condition's slope in its legend.

#include <filesystem>

#include "formats/manifest.h"
#include "stimuli/experiment.h"

namespace countershade {

void write_depth_scale_figures(const Experiment& e, const std::filesystem::path& dir,
                               const Manifest& manifest);

}  // namespace countershade
