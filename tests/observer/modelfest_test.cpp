// The image-computable observer: its contrast sensitivity function is the Spatial Standard
// Observer's published one, its filter applies it at the right frequency and scale, its pooling
// does not depend on the sampling, and fitted to the ModelFest thresholds (built here from their
// definitions) it predicts them within 1.5 dB RMS.

#include "observer/modelfest.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numbers>

#include "core/svg_plot.h"
#include "formats/responses.h"
#include "observer/contrast_sensitivity.h"
#include "observer/detection_model.h"
#include "test_util.h"

namespace countershade::observer {
namespace {

constexpr double kPi = std::numbers::pi;

// The values the reference (tests/reference/modelfest) gives for the published formula.
TEST(ContrastSensitivity, IsTheSpatialStandardObserversFunction) {
  const std::pair<double, double> published[] = {{0, 56.223},  {1, 106.556}, {2, 182.041},
                                                 {4, 214.204}, {8, 135.143}, {16, 43.115},
                                                 {30, 7.166}};
  for (const auto& [f, s] : published) EXPECT_NEAR(sso_sensitivity(f), s, 5e-4) << f << " c/deg";
}

// The filter's frequency response, read from its output for a one-pixel impulse: at every
// frequency of the (padded) grid, the sensitivity at that frequency, times the oblique gain at its
// orientation when asked.
TEST(DetectionModel, TheFilterScalesEachFrequencyByTheSensitivity) {
  const int size = 64;
  const double ppd = 60;
  ContrastImage impulse(size, size);
  impulse.at(size / 2, size / 2) = 1;
  for (bool oblique : {false, true}) {
    const ContrastImage out = csf_filtered(impulse, ppd, oblique);
    const int n = out.width;  // 2·size: the image in its zero surround
    ASSERT_EQ(out.height, n);
    const int k_pairs[][2] = {{0, 0}, {8, 0}, {0, 8}, {8, 8}, {3, 5}, {30, 12}, {-20, 7}};
    for (const auto& k : k_pairs) {
      double re = 0, im = 0;
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const double a = -2 * kPi * (double(k[0]) * x + double(k[1]) * y) / n;
          re += out.at(x, y) * std::cos(a);
          im += out.at(x, y) * std::sin(a);
        }
      const double f = std::hypot(k[0], k[1]) * ppd / n;
      const double theta = std::atan2(double(k[1]), double(k[0]));
      const double expected = sso_sensitivity(f) * (oblique ? oblique_gain(f, theta) : 1.0);
      EXPECT_NEAR(std::hypot(re, im), expected, 1e-9 * expected)
          << "k = (" << k[0] << ", " << k[1] << "), oblique " << oblique;
    }
  }
  EXPECT_LT(oblique_gain(5.66, kPi / 4), 0.95);
  EXPECT_EQ(oblique_gain(5.66, 0), 1.0);
  EXPECT_EQ(oblique_gain(2, kPi / 4), 1.0);
}

// The same blob sampled at 120 and at 240 pixels per degree over the same field in degrees
// gives the same pooled response.
TEST(DetectionModel, ThePooledResponseDoesNotDependOnTheSampling) {
  const auto blob = [](int size, double ppd) {
    ContrastImage image(size, size);
    const double s = 0.1;  // degrees
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const double dx = (x - size / 2) / ppd, dy = (y - size / 2) / ppd;
        image.at(x, y) = 0.02 * std::exp(-(dx * dx + dy * dy) / (2 * s * s));
      }
    return image;
  };
  const DetectionModel model{1, 3, false};
  const double coarse = response_jnd(blob(128, 120), 120, model);
  const double fine = response_jnd(blob(256, 240), 240, model);
  EXPECT_NEAR(fine / coarse, 1.0, 0.01);
  EXPECT_NEAR(response_jnd(blob(128, 120), 120, {2, 3, false}), 2 * coarse, 1e-12);
}

std::vector<ModelfestThreshold> reference_thresholds() {
  const auto path = testing::reference_path("modelfest/thresholds.csv");
  const CsvTable table = parse_csv(testing::read_file(path), path.string());
  std::vector<ModelfestThreshold> out;
  for (size_t r = 1; r < table.rows.size(); ++r)
    out.push_back({std::stoi(table.rows[r][0]), std::stod(table.rows[r][4])});
  return out;
}

// The fit on the 36 stimuli at 120 pixels per degree on 256 × 256 pixels. The goal is 1.5 dB
// RMS (the Spatial Standard Observer reached 1.13 dB on all 43 ModelFest stimuli).
TEST(Modelfest, TheFittedModelPredictsTheThresholdsWithinOneAndAHalfDecibels) {
  const auto stimuli = modelfest_stimuli(120, 256);
  ASSERT_EQ(stimuli.size(), 36u);
  const auto thresholds = reference_thresholds();
  ASSERT_EQ(thresholds.size(), 36u);
  for (const auto& s : stimuli) {
    double peak = 0;
    for (double v : s.image.values) peak = std::max(peak, std::abs(v));
    EXPECT_NEAR(peak, 1.0, 1e-12) << s.number;
  }
  const ModelfestFit fit = fit_modelfest(stimuli, thresholds, 120, false);
  std::string table;
  for (const auto& [family, rms] : rms_by_family(fit))
    table += "  " + family + ": " + std::to_string(rms) + " dB\n";
  std::printf("gain %.4g, beta %.3f, RMS %.3f dB\n%s", fit.model.gain, fit.model.beta, fit.rms_db,
              table.c_str());
  EXPECT_LE(fit.rms_db, 1.5) << table;
  // The model the commands use is this fit.
  EXPECT_NEAR(fit.model.gain, kModelfestModel.gain, 0.005 * kModelfestModel.gain);
  EXPECT_NEAR(fit.model.beta, kModelfestModel.beta, 0.01);

  // docs/figures/modelfest-fit.svg comes from here: COUNTERSHADE_FIGURE_DIR=docs/figures.
  if (const char* figures = std::getenv("COUNTERSHADE_FIGURE_DIR")) {
    LinePlot plot;
    plot.title = "ModelFest thresholds: the model against the measurements (RMS " +
                 std::to_string(fit.rms_db).substr(0, 4) + " dB)";
    plot.x_label = "measured threshold (dB of peak contrast)";
    plot.y_label = "predicted threshold (dB)";
    plot.width = 760;
    plot.height = 520;
    std::vector<std::string> families;
    for (const auto& row : fit.rows) {
      auto at = std::find(families.begin(), families.end(), row.family);
      if (at == families.end()) {
        families.push_back(row.family);
        plot.series.push_back({row.family, {}, {}, plot_color(families.size() - 1), false, true});
        at = families.end() - 1;
      }
      auto& series = plot.series[size_t(at - families.begin())];
      series.x.push_back(row.observed_db);
      series.y.push_back(row.predicted_db);
    }
    plot.series.push_back({"equal", {-45, -8}, {-45, -8}, "#888888", true});
    plot.write(std::filesystem::path(figures) / "modelfest-fit.svg");
  }
}

}  // namespace
}  // namespace countershade::observer
