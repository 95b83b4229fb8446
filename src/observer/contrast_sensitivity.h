#pragma once
// The contrast sensitivity function of the image-computable observer: the Spatial Standard
// Observer's "difference of hyperbolic secants" (Watson & Ahumada 2005), fitted by its authors to
// the ModelFest detection thresholds, and its optional oblique effect (docs/observer.md).

namespace countershade::observer {

// Sensitivity (1 / threshold contrast of a large grating) at f cycles per degree:
// 373.08·[sech((f/4.1726)^0.7786) − 0.8493·sech(f/1.3625)].
double sso_sensitivity(double f);

// The oblique effect's gain at f cycles per degree and orientation θ (radians, 0 for a
// horizontal or vertical wave vector): 1 up to the corner frequency, then falling for oblique
// orientations as sin²(2θ) (Watson & Ahumada 2005).
double oblique_gain(double f, double theta);

}  // namespace countershade::observer
