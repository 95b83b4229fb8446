#pragma once
// Flicker of a stimulus set's sequences (docs/enhancement-methods.md, "Flicker"). For every frame
// that follows another frame of its sequence: the RMS change of the enhancement layer (the
// frame's L* minus its reference frame's L*) at the surface points both frames see, the later
// frame reprojected into the earlier through the frames' geometry and the objects' motion. A
// reference frame records the plain render's own reprojection error (of its L*) instead.
// Measured from the files as written, so a resumed or merged set gets the figures of a set made
// in one run.

#include <filesystem>
#include <vector>

#include "formats/manifest.h"
#include "render/scene.h"
#include "stimuli/experiment.h"

namespace countershade {

// Adds "flicker" (L*) and "flicker_pixels" to the entries of `scene`'s sequences (`base`: the
// scene as the set rendered it), and to enhanced frames "flicker_stable" and
// "flicker_stable_pixels": the same over the pixels whose plain L* reprojects within
// kStableTolerance (stimuli/perspective_coherence.h, rms_where_stable). Frames without an
// earlier frame in the entries get none.
void measure_sequence_flicker(const Experiment& e, const std::filesystem::path& dir,
                              const ExperimentScene& scene, const Scene& base,
                              std::vector<ManifestEntry>& entries, int threads);

}  // namespace countershade
