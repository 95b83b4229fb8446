#pragma once
// The image-computable observer over a stimulus set (docs/observer.md, "countershade predict"):
// each condition's response in JND at every λ of its grid, and the λ at which it reaches 1, 2 and
// 4 JND (near-threshold, preferred and tolerated enhancements, Ritschel et al. 2008, Fig. 12).

#include <array>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/display_calibration_file.h"
#include "formats/manifest.h"
#include "observer/detection_model.h"

namespace countershade::observer {

// The JND levels a prediction reports the λ of.
inline constexpr std::array<double, 3> kPredictionLevels{1, 2, 4};

struct ConditionPrediction {
  std::string scene, method;  // the manifest's scene and condition (label, or method)
  double sigma = 0;
  std::vector<double> lambda, jnd;  // the grid, ascending, and the response at each value
  // The λ where the response first reaches each of kPredictionLevels; none where the grid ends
  // below it. Between two grid values the images are mixed linearly in luminance
  // (docs/observer.md).
  std::array<std::optional<double>, 3> lambda_at;
  double jnd_at_lambda_max() const { return jnd.empty() ? 0 : jnd.back(); }
};

struct SetPrediction {
  std::vector<ConditionPrediction> conditions;  // by scene, condition and σ
  size_t sequence_conditions_skipped = 0;       // the model is static: sequences are left out
};

struct PredictionSettings {
  double ppd = 0;
  CalibratedDisplay display;
  DetectionModel model = kModelfestModel;
  int threads = 0;                       // 0: all cores
  std::function<void(double)> progress;  // fraction of images done, from any thread
};

// Throws InputError naming the image when one cannot be read or differs from its reference in size.
SetPrediction predict_set(const Manifest& manifest, const std::filesystem::path& set_dir,
                          const PredictionSettings& settings);

// The λ in [lambda_a, lambda_b] at which the response reaches `level`, the stimulus taken as the
// luminance mix of the two images whose filtered contrasts are `filtered_a` (below the level) and
// `filtered_b` (at or above it).
double lambda_reaching(double level, const ContrastImage& filtered_a, double lambda_a,
                       const ContrastImage& filtered_b, double lambda_b, double ppd,
                       const DetectionModel& model);

}  // namespace countershade::observer
