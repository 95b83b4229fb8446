#pragma once
// Minimal SVG line and marker plots for figures in reports and docs (no dependencies).

#include <filesystem>
#include <string>
#include <vector>

namespace countershade {

struct PlotSeries {
  std::string label;
  std::vector<double> x, y;
  std::string color = "#1f77b4";
  bool dashed = false;
  bool points = false;  // a marker at each point and no line (measurements)
};

// A vertical interval at x (a confidence interval around a measurement).
struct ErrorBar {
  double x = 0, low = 0, high = 0;
  std::string color = "#1f77b4";
};

struct LinePlot {
  std::string title, x_label, y_label;
  std::vector<PlotSeries> series;
  std::vector<ErrorBar> error_bars;
  int width = 640, height = 400;
  // A logarithmic y axis (values that span decades, such as responses in JND); values ≤ 0 are
  // left out.
  bool log_y = false;

  std::string to_svg() const;
  void write(const std::filesystem::path& path) const;  // atomic
};

// "Nice" tick positions covering [lo, hi]: steps of 1, 2 or 5 × 10^k, at most 7 of them.
std::vector<double> nice_ticks(double lo, double hi);

// Ticks of a logarithmic axis over [lo, hi]: 1, 2 and 5 × 10^k over up to two decades, powers
// of ten over more.
std::vector<double> log_ticks(double lo, double hi);

// A palette of distinguishable colours (colour-blind friendly order).
const std::string& plot_color(size_t index);

}  // namespace countershade
