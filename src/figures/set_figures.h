#pragma once
// Everything drawn from a finished set's manifest: the contact sheets and the figures of its
// measures (congruence, coherence, flicker, scale against depth). `countershade stimuli` draws them
// after a set is generated or merged; they are files of the set, remade from the manifest alone.

#include <filesystem>

#include "formats/manifest.h"
#include "stimuli/experiment.h"

namespace countershade {

// `contact_sheets`: false leaves out the sheets (and the congruence figure's sheet).
void write_set_figures(const Experiment& experiment, const std::filesystem::path& dir,
                       const Manifest& manifest, bool contact_sheets = true);

}  // namespace countershade
