#include "analysis/figures.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>

#include "core/svg_plot.h"
#include "core/xml.h"

namespace countershade::analysis {
namespace {

std::string number(double v, int precision = 3) {
  std::ostringstream s;
  s.precision(precision);
  s << v;
  return s.str();
}

double nice_max(double v) {
  double step = std::pow(10.0, std::floor(std::log10(std::max(v, 1e-9))));
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (m * step >= v) return m * step;
  return 10 * step;
}

const char* kQuestionColours[] = {"#56B4E9", "#D55E00", "#009E73"};  // low, high, best

}  // namespace

namespace {

// Per scene and question: mean and SEM over subjects of their σ-mean JND.
std::vector<std::array<Summary, 3>> scene_question_summaries(const BlockResults& r) {
  std::vector<std::array<Summary, 3>> stats(r.scenes.size());
  for (size_t s = 0; s < r.scenes.size(); ++s)
    for (int q = 0; q < 3; ++q) {
      std::vector<double> v;
      for (size_t i = 0; i < r.subjects.size(); ++i) {
        double m = 0;
        for (size_t g = 0; g < r.sigmas.size(); ++g)
          m += r.jnd.at(i, s, g, Question(q)) / double(r.sigmas.size());
        v.push_back(m);
      }
      stats[s][size_t(q)] = summarize(v);
    }
  return stats;
}

// The bar chart's frame: plot area, value axis from 0 to ymax, in SVG coordinates.
struct BarFrame {
  int width = 720, height = 380, left = 60, right = 120, top = 40, bottom = 50;
  double pw = width - left - right, ph = height - top - bottom, ymax = 1;
  double py(double v) const { return top + ph * (1.0 - v / ymax); }
};

// Gridlines with their values, and the dashed 1 JND reference.
void bar_grid(std::ostringstream& svg, const BarFrame& f) {
  for (int t = 0; t <= 5; ++t) {
    double v = f.ymax * t / 5;
    svg << "<line x1=\"" << f.left << "\" x2=\"" << f.left + f.pw << "\" y1=\"" << f.py(v)
        << "\" y2=\"" << f.py(v) << "\" stroke=\"#e5e5e5\"/><text x=\"" << f.left - 6 << "\" y=\""
        << f.py(v) + 4 << "\" text-anchor=\"end\">" << number(v) << "</text>\n";
  }
  svg << "<line x1=\"" << f.left << "\" x2=\"" << f.left + f.pw << "\" y1=\"" << f.py(1)
      << "\" y2=\"" << f.py(1) << "\" stroke=\"#888\" stroke-dasharray=\"4,3\"/>\n";
}

// One bar with its ±SEM whisker.
void bar_with_error(std::ostringstream& svg, const BarFrame& f, double x, double width,
                    const Summary& st, const char* colour) {
  svg << "<rect x=\"" << x << "\" y=\"" << f.py(st.mean) << "\" width=\"" << width << "\" height=\""
      << f.py(0) - f.py(st.mean) << "\" fill=\"" << colour << "\"/>\n";
  const double cx = x + width / 2;
  svg << "<path d=\"M" << cx << "," << f.py(st.mean - st.sem) << "V" << f.py(st.mean + st.sem)
      << "M" << cx - 4 << "," << f.py(st.mean + st.sem) << "h8M" << cx - 4 << ","
      << f.py(st.mean - st.sem) << "h8\" stroke=\"black\"/>\n";
}

constexpr int kBarOrder[3] = {int(Question::low), int(Question::best), int(Question::high)};

// The plot area's outline, the value axis label and the legend of the three questions.
void bar_frame_and_legend(std::ostringstream& svg, const BarFrame& f) {
  svg << "<rect x=\"" << f.left << "\" y=\"" << f.top << "\" width=\"" << f.pw << "\" height=\""
      << f.ph << "\" fill=\"none\" stroke=\"#444\"/>\n<text transform=\"translate(16,"
      << f.top + f.ph / 2 << ") rotate(-90)\" text-anchor=\"middle\">λ (JND)</text>\n";
  const char* names[3] = {"λ_Low", "λ_Best", "λ_High"};
  for (int k = 0; k < 3; ++k)
    svg << "<rect x=\"" << f.left + f.pw + 14 << "\" y=\"" << f.top + 10 + 20 * k
        << "\" width=\"14\" height=\"12\" fill=\"" << kQuestionColours[kBarOrder[k]]
        << "\"/><text x=\"" << f.left + f.pw + 34 << "\" y=\"" << f.top + 21 + 20 * k << "\">"
        << names[k] << "</text>\n";
}

}  // namespace

std::string figure_questions_by_scene(const BlockResults& r) {
  const size_t ns = r.scenes.size();
  const std::vector<std::array<Summary, 3>> stats = scene_question_summaries(r);
  double top_value = 0;
  for (const auto& scene : stats)
    for (const Summary& st : scene) top_value = std::max(top_value, st.mean + st.sem);
  BarFrame f;
  f.ymax = nice_max(top_value * 1.05);
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << f.width << "\" height=\""
      << f.height
      << "\" font-family=\"sans-serif\" font-size=\"12\"><rect width=\"100%\" height=\"100%\" "
         "fill=\"white\"/>\n"
      << "<text x=\"" << f.width / 2
      << "\" y=\"22\" text-anchor=\"middle\" font-size=\"14\">Chosen λ in JND per scene (mean ± "
         "SEM, n = "
      << r.subjects.size() << ")</text>\n";
  bar_grid(svg, f);
  const double group = f.pw / double(ns), bar = group * 0.22;
  for (size_t s = 0; s < ns; ++s) {
    const double x0 = f.left + group * double(s) + group * 0.17;
    for (int k = 0; k < 3; ++k)
      bar_with_error(svg, f, x0 + bar * k, bar - 2, stats[s][size_t(kBarOrder[k])],
                     kQuestionColours[kBarOrder[k]]);
    svg << "<text x=\"" << f.left + group * (double(s) + 0.5) << "\" y=\"" << f.top + f.ph + 18
        << "\" text-anchor=\"middle\">" << xml_escape(r.scenes[s]) << "</text>\n";
  }
  bar_frame_and_legend(svg, f);
  svg << "</svg>\n";
  return svg.str();
}

std::string figure_lambda_by_sigma(const BlockResults& r) {
  LinePlot plot;
  plot.title = "Chosen λ in JND against σ (solid: λ_Best, dashed: λ_High)";
  plot.x_label = "σ";
  plot.y_label = "λ (JND)";
  plot.width = 720;
  for (size_t s = 0; s < r.scenes.size(); ++s)
    for (Question q : {Question::best, Question::high}) {
      PlotSeries series;
      series.label = r.scenes[s] + (q == Question::best ? " best" : " high");
      series.color = plot_color(s);
      series.dashed = q == Question::high;
      for (size_t g = 0; g < r.sigmas.size(); ++g) {
        double m = 0;
        for (size_t i = 0; i < r.subjects.size(); ++i)
          m += r.jnd.at(i, s, g, q) / double(r.subjects.size());
        series.x.push_back(r.sigmas[g]);
        series.y.push_back(m);
      }
      plot.series.push_back(series);
    }
  return plot.to_svg();
}

namespace {

// One panel of the fit figure: the empirical CDF of the answers (steps), the fitted CDF, the
// threshold (dashed, labelled) and numeric axes.
struct FitPanel {
  double x0, y0, width, height, lmax;
  double px(double l) const { return x0 + width * l / lmax; }
  double py(double p) const { return y0 + height * (1.0 - p); }

  void axes(std::ostringstream& svg) const {
    svg << "<rect x=\"" << x0 << "\" y=\"" << y0 << "\" width=\"" << width << "\" height=\""
        << height << "\" fill=\"none\" stroke=\"#888\"/>\n";
    for (double t : nice_ticks(0.0, lmax))
      svg << "<line x1=\"" << px(t) << "\" x2=\"" << px(t) << "\" y1=\"" << py(0) << "\" y2=\""
          << py(0) + 4 << "\" stroke=\"#444\"/><text x=\"" << px(t) << "\" y=\"" << py(0) + 14
          << "\" text-anchor=\"middle\">" << number(t) << "</text>\n";
    for (double p : {0.0, 0.5, 1.0})
      svg << "<line x1=\"" << x0 - 4 << "\" x2=\"" << x0 << "\" y1=\"" << py(p) << "\" y2=\""
          << py(p) << "\" stroke=\"#444\"/><text x=\"" << x0 - 6 << "\" y=\"" << py(p) + 3
          << "\" text-anchor=\"end\">" << number(p) << "</text>\n";
    svg << "<text x=\"" << x0 + width << "\" y=\"" << py(0) + 26
        << "\" text-anchor=\"end\">λ</text>\n";
  }

  void curves(std::ostringstream& svg, const BlockResults::FitEntry& f) const {
    const char* colour = kQuestionColours[int(f.question)];
    std::vector<double> a = f.answers;
    std::sort(a.begin(), a.end());
    svg << "<path fill=\"none\" stroke=\"#444\" d=\"M" << px(0) << "," << py(0);
    for (size_t i = 0; i < a.size(); ++i)
      svg << "H" << px(a[i]) << "V" << py(double(i + 1) / double(a.size()));
    svg << "H" << px(lmax) << "\"/>\n<polyline fill=\"none\" stroke=\"" << colour
        << "\" stroke-width=\"1.8\" points=\"";
    for (int t = 0; t <= 100; ++t)
      svg << px(lmax * t / 100.0) << "," << py(fit_cdf(f.fit, lmax * t / 100.0)) << " ";
    svg << "\"/>\n";
    if (!(f.fit.threshold <= lmax)) return;  // the median lies beyond the axis
    svg << "<line x1=\"" << px(f.fit.threshold) << "\" x2=\"" << px(f.fit.threshold) << "\" y1=\""
        << py(0) << "\" y2=\"" << py(0.5) << "\" stroke=\"" << colour
        << "\" stroke-dasharray=\"3,2\"/>\n<text x=\"" << px(f.fit.threshold) + 3 << "\" y=\""
        << py(0.5) - 3 << "\">" << number(f.fit.threshold) << "</text>\n";
  }
};

// A panel's title: the cell, n, and how many answers were censored at either end of the grid.
std::string panel_title(const BlockResults::FitEntry& f) {
  std::string title = xml_escape(f.scene) + ", σ=" + number(f.sigma) + ", " +
                      kQuestionNames[int(f.question)] + " (n=" + std::to_string(f.fit.n);
  if (f.fit.left_censored) title += ", " + std::to_string(f.fit.left_censored) + " at first";
  if (f.fit.right_censored) title += ", " + std::to_string(f.fit.right_censored) + " at top";
  if (!f.fit.identified) title += ", unidentified";
  return title + ")";
}

}  // namespace

std::string figure_fits(const BlockResults& r) {
  const int cols = 3, rows = int((r.fits.size() + 2) / 3), pw = 220, ph = 110, gap_x = 56,
            gap_y = 64;
  const int width = cols * (pw + gap_x) + gap_x, height = rows * (ph + gap_y) + 64;
  // One λ range per question (column): λ_Low answers are much smaller than λ_High ones.
  double column_max[3] = {0, 0, 0};
  for (const auto& f : r.fits)
    for (double a : f.answers)
      column_max[int(f.question)] = std::max(column_max[int(f.question)], a);
  for (double& m : column_max) m = nice_max(m * 1.05);
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" font-family=\"sans-serif\" font-size=\"10\"><rect width=\"100%\" height=\"100%\" "
         "fill=\"white\"/>\n"
      << "<text x=\"" << width / 2 << "\" y=\"20\" text-anchor=\"middle\" font-size=\"14\">Fitted "
      << (r.fits.empty() ? "" : threshold_model_name(r.fits[0].fit.model))
      << " threshold distributions (lines; dashed: the threshold)</text>\n<text x=\"" << width / 2
      << "\" y=\"36\" text-anchor=\"middle\" font-size=\"11\">steps: the share of answers at or "
         "below λ</text>\n";
  for (size_t k = 0; k < r.fits.size(); ++k) {
    const auto& f = r.fits[k];
    const FitPanel panel{gap_x + double(k % cols) * (pw + gap_x),
                         64 + double(k / cols) * (ph + gap_y), double(pw), double(ph),
                         column_max[int(f.question)]};
    svg << "<text x=\"" << panel.x0 << "\" y=\"" << panel.y0 - 5 << "\">" << panel_title(f)
        << "</text>\n";
    panel.axes(svg);
    panel.curves(svg, f);
  }
  svg << "</svg>\n";
  return svg.str();
}

std::string figure_dendrogram(const BlockResults& r) {
  const Dendrogram& d = r.dendrogram;
  const size_t n = r.subjects.size();
  // The leaves' labels, "subject (cluster)", run downwards at about 7 px a character.
  size_t longest = 0;
  for (const auto& s : r.subjects) longest = std::max(longest, s.size() + 5);
  const int bottom = std::max(60, 16 + 7 * int(longest)), height = 300 + bottom;
  const int width = std::max(560, int(n) * 28 + 120), left = 60, top = 40;
  const double pw = width - left - 40, ph = height - top - bottom;
  double hmax = d.heights.empty() ? 1.0 : nice_max(d.heights.back());
  std::vector<double> leaf_x(n);
  for (size_t k = 0; k < d.order.size(); ++k)
    leaf_x[size_t(d.order[k])] = left + pw * (double(k) + 0.5) / double(n);
  auto py = [&](double h) { return top + ph * (1.0 - h / hmax); };
  std::vector<double> node_x(d.merges.size());
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" font-family=\"sans-serif\" font-size=\"11\"><rect width=\"100%\" height=\"100%\" "
         "fill=\"white\"/>\n"
      << "<text x=\"" << width / 2
      << "\" y=\"22\" text-anchor=\"middle\" font-size=\"14\">Ward (ward.D2) clustering of "
         "subjects by their per-scene λ_Best (JND)</text>\n";
  auto position = [&](int node) -> std::pair<double, double> {
    return node < 0 ? std::pair{leaf_x[size_t(-node - 1)], 0.0}
                    : std::pair{node_x[size_t(node)], d.heights[size_t(node)]};
  };
  for (size_t m = 0; m < d.merges.size(); ++m) {
    auto [xa, ha] = position(d.merges[m].first);
    auto [xb, hb] = position(d.merges[m].second);
    node_x[m] = 0.5 * (xa + xb);
    double h = d.heights[m];
    svg << "<path fill=\"none\" stroke=\"#333\" d=\"M" << xa << "," << py(ha) << "V" << py(h) << "H"
        << xb << "V" << py(hb) << "\"/>\n";
  }
  for (size_t i = 0; i < n; ++i)
    svg << "<text transform=\"translate(" << leaf_x[i] + 4 << "," << top + ph + 8
        << ") rotate(90)\" fill=\"" << plot_color(size_t(r.cluster_labels[i] - 1)) << "\">"
        << xml_escape(r.subjects[i]) << " (" << r.cluster_labels[i] << ")</text>\n";
  svg << "<line x1=\"" << left - 8 << "\" x2=\"" << left - 8 << "\" y1=\"" << py(0) << "\" y2=\""
      << py(hmax) << "\" stroke=\"#444\"/>\n";
  for (double t : nice_ticks(0.0, hmax))
    svg << "<line x1=\"" << left - 12 << "\" x2=\"" << left - 8 << "\" y1=\"" << py(t) << "\" y2=\""
        << py(t) << "\" stroke=\"#444\"/><text x=\"" << left - 14 << "\" y=\"" << py(t) + 4
        << "\" text-anchor=\"end\">" << number(t) << "</text>\n";
  svg << "<text transform=\"translate(16," << top + ph / 2
      << ") rotate(-90)\" text-anchor=\"middle\">merge height (Ward, JND)</text>\n</svg>\n";
  return svg.str();
}

}  // namespace countershade::analysis
