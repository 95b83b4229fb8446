#include "figures/condition_lines.h"

#include <gtest/gtest.h>

namespace countershade {
namespace {

ManifestEntry entry(const std::string& label, double sigma) {
  ManifestEntry s;
  s.method = label.empty() ? kReferenceMethod : label;
  s.label = label;
  if (!label.empty()) s.sigma = sigma;
  return s;
}

// A method keeps its colour in every plot of a set, whichever other lines a plot holds (a stable
// flicker plot has no plain line, a scene may lack a method); the plain render is grey and dashed.
TEST(ConditionLines, AMethodHasOneColourInEveryPlot) {
  Experiment e;
  for (const char* label : {"usm3d", "usm2d", "depth-usm-darken"}) {
    ExperimentMethod m;
    m.label = label;
    m.sigmas = {1.0};
    e.methods.push_back(m);
  }
  LinePlot with_plain, without_plain;
  ConditionLines a(e, with_plain), b(e, without_plain);
  for (const char* label : {"", "usm3d", "usm2d", "depth-usm-darken"}) a.line_of(entry(label, 1.0));
  for (const char* label : {"depth-usm-darken", "usm2d"}) b.line_of(entry(label, 1.0));
  ASSERT_EQ(with_plain.series.size(), 4u);
  ASSERT_EQ(without_plain.series.size(), 2u);
  EXPECT_EQ(with_plain.series[0].label, "plain");
  EXPECT_EQ(with_plain.series[0].color, "#777777");
  EXPECT_TRUE(with_plain.series[0].dashed);
  EXPECT_EQ(with_plain.series[1].color, plot_color(0));
  EXPECT_EQ(with_plain.series[2].color, plot_color(1));
  EXPECT_EQ(with_plain.series[3].color, plot_color(2));
  EXPECT_EQ(without_plain.series[0].color, plot_color(2));  // depth-usm-darken, as above
  EXPECT_EQ(without_plain.series[1].color, plot_color(1));  // usm2d
  EXPECT_NE(plot_color(0), plot_color(1));
}

}  // namespace
}  // namespace countershade
