#pragma once
// What `countershade predict` writes (docs/observer.md): predicted_thresholds.csv,
// predicted_jnd.csv, report.html (one JND-against-λ plot per scene and per condition) and the
// scenes' plots as jnd-<scene>.svg.

#include <filesystem>
#include <string>

#include "observer/set_prediction.h"

namespace countershade::observer {

// How the images were seen, for the report's heading.
struct PredictionContext {
  std::string set_name, manifest, display;  // display: in words ("sRGB, white at 100 cd/m²")
  double ppd = 0;
  DetectionModel model = kModelfestModel;
};

// Four significant digits: the model is no more certain than that (docs/observer.md, "Limits").
std::string rounded(double v);

// scene,method,sigma,lambda_1jnd,lambda_2jnd,lambda_4jnd,jnd_at_lambda_max; a level the grid does
// not reach is an empty field.
std::string predicted_thresholds_csv(const SetPrediction& prediction);
// scene,method,sigma,lambda,jnd: every image's response.
std::string predicted_jnd_csv(const SetPrediction& prediction);
std::string prediction_report_html(const SetPrediction& prediction,
                                   const PredictionContext& context);

// Writes the files into `dir` (created if missing), each atomically.
void write_prediction(const std::filesystem::path& dir, const SetPrediction& prediction,
                      const PredictionContext& context);

}  // namespace countershade::observer
