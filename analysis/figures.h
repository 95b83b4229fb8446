#pragma once
// SVG figures of an analysis, in the style of Ritschel et al. 2008 (Figs. 12 and 13).

#include <string>

#include "analysis/analysis.h"

namespace countershade::analysis {

// Fig. 12: λ_Low, λ_Best and λ_High in JND per scene, bars with SEM error bars.
std::string figure_questions_by_scene(const BlockResults& results);
// Fig. 13: λ (JND) against σ per scene, for λ_Best (solid) and λ_High (dashed).
std::string figure_lambda_by_sigma(const BlockResults& results);
// Fitted threshold CDFs over each condition's empirical cumulative distribution (small multiples).
std::string figure_fits(const BlockResults& results);
// The Ward dendrogram of subjects, coloured by cluster.
std::string figure_dendrogram(const BlockResults& results);

}  // namespace countershade::analysis
