#pragma once
// The ModelFest stimuli (Carney et al. 1999; Watson & Ahumada 2005), built from their definitions
// as contrast images, and the detection model's fit to their thresholds (docs/observer.md).

#include <string>
#include <vector>

#include "observer/detection_model.h"

namespace countershade::observer {

struct ModelfestStimulus {
  int number = 0;       // ModelFest's stimulus number
  std::string family;   // "Gabor s=0.5°", "compound Gabors", …: the error is stated per family
  ContrastImage image;  // peak |contrast| 1
};

// Stimuli 1–25, 27, 29, 31, 33, 34, 36–39, 41 and 42 at `ppd` pixels per degree on a
// size × size field (ModelFest: 120 and 256).
std::vector<ModelfestStimulus> modelfest_stimuli(double ppd = 120, int size = 256);

struct ModelfestThreshold {
  int number = 0;
  double threshold_db = 0;  // 20·log10(peak threshold contrast)
};

struct ModelfestFit {
  DetectionModel model;
  struct Row {
    int number = 0;
    std::string family;
    double observed_db = 0, predicted_db = 0;
  };
  std::vector<Row> rows;
  double rms_db = 0;  // over every stimulus
};

// The gain and β that minimise the RMS error in dB of the predicted thresholds (the contrast at
// which the response is 1 JND), β in [1, 8]; with `oblique`, the oblique effect filters too.
// Every stimulus must have a threshold.
ModelfestFit fit_modelfest(const std::vector<ModelfestStimulus>& stimuli,
                           const std::vector<ModelfestThreshold>& thresholds, double ppd,
                           bool oblique);

// The RMS error in dB of each family, in the order they first appear.
std::vector<std::pair<std::string, double>> rms_by_family(const ModelfestFit& fit);

}  // namespace countershade::observer
