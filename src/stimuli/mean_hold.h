#pragma once
// Holding a stimulus's mean lightness at its reference's (an experiment's "hold_mean"). 3D unsharp
// masking brightens a scene as λ grows by its design (its contrast is taken against surface the
// camera does not see), and observers may judge that brightening instead of the enhancement. This
// is a study-design choice on top of a method, not part of any method: the stimulus's object
// pixels are shifted by one uniform L* offset, through the lightness-only rule (hue and chroma
// kept), until the mean L* of the image as written equals the reference's.

#include <cstddef>
#include <functional>
#include <optional>
#include <span>

#include "core/image.h"
#include "enhance/method.h"
#include "enhance/view.h"

namespace countershade {

struct HeldMean {
  Image display;              // the stimulus with its offset, code values of the view's bit depth
  double offset = 0;          // the L* offset δ applied to every object pixel
  size_t clipped_pixels = 0;  // clipped pixels (L' outside [0, 100] or a channel outside [0, 1]),
                              // the stimulus's own included
};

// The stimulus composed again with an L* offset on the pixels `where` marks, before its one
// quantisation (PreparedEnhancement::compose_offset); empty when its method cannot.
using OffsetComposer =
    std::function<std::optional<Composed>(double offset, std::span<const double> where)>;

// `stimulus`: a stimulus of `view` as its method composed it (code values, rounded to view.bits
// or not yet: RGB operators leave that to the writer) and its clipped pixels. Object pixels are
// those with a finite, positive depth (every pixel when the view has no depth). The offset is
// found to within `tolerance` L* of the reference's mean, measured over the whole image decoded
// from its codes (as the audit measures drift); a stimulus equal to the view's image is returned
// unchanged. With `recompose`, each offset tried is composed by the method with its change;
// else it is added to the stimulus as given. Either way the result is rounded once; a stimulus
// given already rounded rounds twice, and its uniform faces move by whole codes.
HeldMean hold_mean_lightness(const View& view, const Composed& stimulus, double tolerance = 0.005,
                             const OffsetComposer& recompose = {});

// The stimulus `prepared` composed at λ, held: each offset tried is composed by its method where
// it can (PreparedEnhancement::compose_offset).
HeldMean hold_mean_lightness(const View& view, const PreparedEnhancement& prepared, double lambda,
                             const Composed& stimulus);

}  // namespace countershade
