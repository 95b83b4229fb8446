#pragma once
// The congruence score between shading flow and shape flow (Mestres et al. 2021, eq. 2, after
// Vergne et al. 2016), exactly as docs/methods.md defines it ("Congruence score"):
// structure tensors of L*/100 and of the normalised depth, smoothed with a Gaussian of σ = 2 px,
// their dominant orientations and mean eigenvalues, and a weighted agreement over the interior
// pixels. 1 means the shading varies exactly where and along the shape varies; a flat image is 0.

#include <cstddef>
#include <vector>

#include "core/display.h"
#include "core/image.h"

namespace countershade {

// How a difference of magnitudes lowers a pixel's term e_c·(1 − ⌊d⌋)·|v_c·v_s| (⌊·⌋ clamps to
// [0, 1]). `signed_clamp`, the paper's: d = e_c − e_s, so shading stronger than shape
// (exaggeration) costs nothing. `absolute`: d = |e_c − e_s|, which also penalises exaggeration;
// an earlier reading, kept to reproduce figures made with it.
enum class CongruencePenalty { signed_clamp, absolute };

struct CongruenceOptions {
  CongruencePenalty penalty = CongruencePenalty::signed_clamp;
  double tensor_sigma = 2;  // σ_t of the structure tensors' Gaussian, pixels (truncated at 4σ_t)
};

struct Congruence {
  double score = 0;            // s in [0, 1]
  size_t interior_pixels = 0;  // foreground pixels whose 3×3 neighbourhood is all foreground
  Image map;  // per pixel: e_c·(1 − ⌊d⌋)·|v_c·v_s| (0 outside the interior)
};

// `lightness`: one channel of CIELAB L* (0…100); `depth`: one channel of the same size, where
// foreground pixels have a finite, positive depth (0, inf and NaN are background).
// Throws std::invalid_argument when the sizes differ or an image is not one channel.
Congruence congruence(const Image& lightness, const Image& depth,
                      const CongruenceOptions& options = {});

// The score of a display image (decoded with `encoding` at `bits`, 0 = float) against a depth
// buffer of the same size (values as for `congruence`).
Congruence display_congruence(const Image& display, const DisplayEncoding& encoding, int bits,
                              const std::vector<float>& depth,
                              const CongruenceOptions& options = {});

// The 99th-percentile rule's percentile: linear interpolation between order statistics
// (x sorted, h = (n − 1)·p, x[⌊h⌋] + (h − ⌊h⌋)·(x[⌊h⌋+1] − x[⌊h⌋]); R's type 7); 0 for no values.
double percentile(std::vector<float> values, double p);

}  // namespace countershade
