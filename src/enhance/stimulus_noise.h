#pragma once
// The sampling noise of a written stimulus, estimated from its view: what two renders with
// different seeds would measure. Per pixel, the view's L* standard error (from the renderer's two
// replicates) goes through the method's noise model (amplification by the gain, the smoothed
// signal's own error), then through the quantisation to code values, which rounds small
// differences away or up to a whole step.

#include <vector>

#include "core/image.h"
#include "enhance/method.h"

namespace countershade {

struct NoiseSummary {
  double rms = 0;  // over all pixels, L*
  double p99 = 0;  // the 99th percentile of the absolute L* error over pixels
};

// The noise of L + λ·c per pixel before quantisation, from the view's noise and the render's
// estimate for the change c (none: the view's noise), plus an independent term |λ|·extra[p]
// (e.g. the error of a smoothed vertex signal, which every replicate shares).
NoiseModel lambda_noise(const View& view, const ChangeNoise* change, double lambda,
                        const std::vector<float>& extra = {});

// Per pixel, the estimated standard deviation of the written stimulus's L* between seeds.
std::vector<float> stimulus_noise(const View& view, const NoiseModel& model, const Image& written);

// The RMS and the 99th percentile of |error| over pixels, each pixel's error normal with its σ.
NoiseSummary summarize_noise(const std::vector<float>& sigma);

// The quantisation's effect on a normal error of standard deviation r·q (q the L* step of one
// code): the root mean square of the difference of two independently rounded values, over √2,
// in steps. 0 at r = 0, √(r/√π) for small r (a rounding flips with probability ∝ r), √(r² + 1/12)
// for large r.
double quantized_noise_steps(double r);

}  // namespace countershade
