// Line plots: ticks cover the data, and a long legend label fits inside the figure.

#include "core/svg_plot.h"

#include <gtest/gtest.h>

#include <regex>

namespace countershade {
namespace {

TEST(SvgPlot, NiceTicksCoverTheRangeInSteps) {
  const std::vector<double> ticks = nice_ticks(0.13, 0.87);
  ASSERT_GE(ticks.size(), 3u);
  EXPECT_LE(ticks.size(), 7u);
  EXPECT_GE(ticks.front(), 0.13 - 1e-12);
  EXPECT_LE(ticks.back(), 0.87 + 1e-12);
}

// The legend starts right of the plot area; a 40-character label needs about 280 px after it.
TEST(SvgPlot, ALongLegendLabelFitsInTheFigure) {
  LinePlot plot;
  plot.width = 640;
  const std::string label(40, 'x');
  plot.series.push_back({label, {0, 1}, {0, 1}});
  const std::string svg = plot.to_svg();
  std::smatch m;
  ASSERT_TRUE(
      std::regex_search(svg, m, std::regex("<text x=\"([0-9.]+)\" y=\"[0-9.]+\">" + label)));
  EXPECT_LE(std::stod(m[1]) + 7.0 * double(label.size()), 640.0);
}

}  // namespace
}  // namespace countershade
