#include "core/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/atomic_file.h"
#include "core/xml.h"

namespace countershade {

std::vector<double> nice_ticks(double lo, double hi) {
  double span = hi - lo;
  if (!(span > 0)) return {lo};
  double step = std::pow(10.0, std::floor(std::log10(span / 5)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (span / (step * m) <= 7) {
      step *= m;
      break;
    }
  std::vector<double> out;
  for (double t = std::ceil(lo / step) * step; t <= hi + 1e-9 * span; t += step)
    out.push_back(std::abs(t) < 1e-12 * span ? 0 : t);
  return out;
}

std::vector<double> log_ticks(double lo, double hi) {
  std::vector<double> out;
  if (!(lo > 0) || !(hi >= lo)) return out;
  const bool few_decades = std::log10(hi / lo) <= 2;
  for (int k = int(std::floor(std::log10(lo))); k <= int(std::ceil(std::log10(hi))); ++k)
    for (double m : {1.0, 2.0, 5.0}) {
      const double t = m * std::pow(10.0, k);
      if ((m == 1.0 || few_decades) && t >= lo * (1 - 1e-9) && t <= hi * (1 + 1e-9))
        out.push_back(t);
    }
  return out;
}

const std::string& plot_color(size_t index) {
  static const std::vector<std::string> palette = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                                   "#E69F00", "#56B4E9", "#000000", "#F0E442",
                                                   "#882255", "#44AA99", "#999933", "#AA4499"};
  return palette[index % palette.size()];
}

namespace {

// Where a LinePlot draws: the data ranges (y padded by 5 %) and the plot area inside the margins.
// On a logarithmic axis y0 and y1 are log10 of the range.
struct PlotFrame {
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  double left = 70, right = 150, top = 40, bottom = 55, pw = 0, ph = 0;
  bool log_y = false;
  double px(double x) const { return left + (x - x0) / (x1 - x0) * pw; }
  double py(double y) const {
    return top + (1.0 - ((log_y ? std::log10(y) : y) - y0) / (y1 - y0)) * ph;
  }
  bool shows(double y) const { return !log_y || y > 0; }
  double axis_value(double y) const { return log_y ? std::log10(y) : y; }
};

PlotFrame plot_frame(const LinePlot& plot) {
  PlotFrame f;
  f.log_y = plot.log_y;
  for (const auto& s : plot.series)
    for (size_t i = 0; i < s.x.size(); ++i) {
      if (!f.shows(s.y[i])) continue;
      f.x0 = std::min(f.x0, s.x[i]);
      f.x1 = std::max(f.x1, s.x[i]);
      f.y0 = std::min(f.y0, f.axis_value(s.y[i]));
      f.y1 = std::max(f.y1, f.axis_value(s.y[i]));
    }
  for (const ErrorBar& e : plot.error_bars) {
    if (!f.shows(e.low)) continue;
    f.y0 = std::min(f.y0, f.axis_value(e.low));
    f.y1 = std::max(f.y1, f.axis_value(e.high));
  }
  if (f.x0 > f.x1) f.x0 = 0, f.x1 = 1, f.y0 = 0, f.y1 = 1;
  const double pad = 0.05 * (f.y1 - f.y0 > 0 ? f.y1 - f.y0 : 1.0);
  f.y0 -= pad;
  f.y1 += pad;
  if (f.x1 == f.x0) f.x1 = f.x0 + 1;
  size_t longest = 0;  // the legend's widest label sets the right margin (about 7 px a character)
  for (const auto& s : plot.series) longest = std::max(longest, s.label.size());
  f.right = std::max(150.0, 48.0 + 7.0 * double(longest));
  f.pw = plot.width - f.left - f.right;
  f.ph = plot.height - f.top - f.bottom;
  return f;
}

// Gridlines with tick values, the plot area's outline and the axis labels.
void plot_axes(std::ostringstream& svg, const LinePlot& plot, const PlotFrame& f) {
  for (double t : nice_ticks(f.x0, f.x1))
    svg << "<line x1=\"" << f.px(t) << "\" y1=\"" << f.top << "\" x2=\"" << f.px(t) << "\" y2=\""
        << f.top + f.ph << "\" stroke=\"#e5e5e5\"/><text x=\"" << f.px(t) << "\" y=\""
        << f.top + f.ph + 16 << "\" text-anchor=\"middle\">" << t << "</text>\n";
  const std::vector<double> y_ticks =
      f.log_y ? log_ticks(std::pow(10.0, f.y0), std::pow(10.0, f.y1)) : nice_ticks(f.y0, f.y1);
  for (double t : y_ticks)
    svg << "<line x1=\"" << f.left << "\" y1=\"" << f.py(t) << "\" x2=\"" << f.left + f.pw
        << "\" y2=\"" << f.py(t) << "\" stroke=\"#e5e5e5\"/><text x=\"" << f.left - 6 << "\" y=\""
        << f.py(t) + 4 << "\" text-anchor=\"end\">" << t << "</text>\n";
  svg << "<rect x=\"" << f.left << "\" y=\"" << f.top << "\" width=\"" << f.pw << "\" height=\""
      << f.ph << "\" fill=\"none\" stroke=\"#444\"/>\n"
      << "<text x=\"" << f.left + f.pw / 2 << "\" y=\"" << plot.height - 12
      << "\" text-anchor=\"middle\">" << xml_escape(plot.x_label) << "</text>\n"
      << "<text transform=\"translate(16," << f.top + f.ph / 2
      << ") rotate(-90)\" text-anchor=\"middle\">" << xml_escape(plot.y_label) << "</text>\n";
}

// One series as a polyline, and its legend entry (row k) when it has a label.
void plot_series(std::ostringstream& svg, const PlotSeries& s, size_t k, const PlotFrame& f) {
  const double ly = f.top + 14 + 18 * double(k);
  if (s.points) {
    for (size_t i = 0; i < s.x.size(); ++i)
      if (f.shows(s.y[i]))
        svg << "<circle cx=\"" << f.px(s.x[i]) << "\" cy=\"" << f.py(s.y[i])
            << "\" r=\"3.5\" fill=\"" << s.color << "\"/>";
    svg << "\n";
    if (!s.label.empty())
      svg << "<circle cx=\"" << f.left + f.pw + 21 << "\" cy=\"" << ly << "\" r=\"3.5\" fill=\""
          << s.color << "\"/><text x=\"" << f.left + f.pw + 38 << "\" y=\"" << ly + 4 << "\">"
          << xml_escape(s.label) << "</text>\n";
    return;
  }
  svg << "<polyline fill=\"none\" stroke=\"" << s.color << "\" stroke-width=\"1.8\""
      << (s.dashed ? " stroke-dasharray=\"5,3\"" : "") << " points=\"";
  for (size_t i = 0; i < s.x.size(); ++i)
    if (f.shows(s.y[i])) svg << f.px(s.x[i]) << "," << f.py(s.y[i]) << " ";
  svg << "\"/>\n";
  if (s.label.empty()) return;
  svg << "<line x1=\"" << f.left + f.pw + 10 << "\" y1=\"" << ly << "\" x2=\"" << f.left + f.pw + 32
      << "\" y2=\"" << ly << "\" stroke=\"" << s.color << "\" stroke-width=\"2\""
      << (s.dashed ? " stroke-dasharray=\"5,3\"" : "") << "/><text x=\"" << f.left + f.pw + 38
      << "\" y=\"" << ly + 4 << "\">" << xml_escape(s.label) << "</text>\n";
}

}  // namespace

std::string LinePlot::to_svg() const {
  const PlotFrame f = plot_frame(*this);
  std::ostringstream svg;
  svg.precision(6);
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"" << width / 2 << "\" y=\"22\" text-anchor=\"middle\" font-size=\"14\">"
      << xml_escape(title) << "</text>\n";
  plot_axes(svg, *this, f);
  for (const ErrorBar& e : error_bars)
    if (f.shows(e.low))
      svg << "<line x1=\"" << f.px(e.x) << "\" y1=\"" << f.py(e.low) << "\" x2=\"" << f.px(e.x)
          << "\" y2=\"" << f.py(e.high) << "\" stroke=\"" << e.color
          << "\" stroke-width=\"1.2\"/>\n";
  size_t row = 0;  // legend rows: only labelled series take one
  for (const PlotSeries& s : series) plot_series(svg, s, s.label.empty() ? row : row++, f);
  svg << "</svg>\n";
  return svg.str();
}

void LinePlot::write(const std::filesystem::path& path) const {
  write_text_atomically(path, to_svg());
}

}  // namespace countershade
