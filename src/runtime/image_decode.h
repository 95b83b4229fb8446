#pragma once
// Stimuli as the app's textures take them: 8- or 16-bit RGBA (the set's depth), checked against
// the manifest's size.

#include <cstdint>
#include <optional>
#include <vector>

#include "runtime/fine_levels.h"
#include "runtime/presenter.h"
#include "runtime/session_run.h"
#include "runtime/study.h"

namespace countershade::runtime {

// Decodes a stimulus into 8-bit (or 16-bit) RGBA; the size must be the manifest's. Throws
// InputError.
std::vector<uint8_t> decode_rgba(const StimulusImage& image);
std::vector<uint16_t> decode_rgba16(const StimulusImage& image);

// With `--output-path pseudo-grey` and a 16-bit set: every image must be achromatic (R, G and B
// within kAchromaticSpread codes at every pixel); throws InputError naming the first image and
// pixel that is not. Run before a window opens or a session file is written.
void require_achromatic_images(const Study& study, const OutputPathChoice& path);

// Every image of the study as a texture (by image index), decoded in parallel and uploaded in
// batches of eight, with a progress bar; timed for the run's record (`preload` in the sidecar).
struct Preloaded {
  std::optional<std::vector<unsigned>> textures;  // none: the window was closed meanwhile
  Preload record;
};
Preloaded preload_study(Presenter& presenter, const Study& study);

}  // namespace countershade::runtime
