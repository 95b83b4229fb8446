#pragma once
// Radiance scaling's pieces (the method lives in radiance_scaling.cpp), for tests.

namespace countershade {

// σ(κ, δ) for the invariant point α and strength γ: the factor on a light sample's reflected
// radiance; σ(0, δ) = 1 and σ(κ, α) = 1.
double radiance_scale(double kappa, double delta, double alpha, double gamma);

}  // namespace countershade
