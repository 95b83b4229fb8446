#include "figures/depth_scale_figures.h"

#include <cmath>
#include <sstream>

#include "core/atomic_file.h"
#include "core/number_format.h"
#include "core/svg_plot.h"
#include "figures/condition_lines.h"

namespace countershade {
namespace {

void write_table(const std::filesystem::path& path, const Experiment& e,
                 const std::vector<const ManifestEntry*>& entries) {
  std::ostringstream csv;
  csv << "scene,condition,lambda,edge_x,depth,halo_width_px\n";
  for (const ManifestEntry* s : entries) {
    const auto& h = s->extra["halo_widths"];
    for (size_t i = 0; i < h["depth"].size(); ++i)
      csv << condition_columns(e, *s) << format_value(h["edge_x"][i].get<double>()) << ','
          << format_value(h["depth"][i].get<double>()) << ','
          << format_value(h["width_px"][i].get<double>()) << '\n';
  }
  write_text_atomically(path, csv.str());
}

// Points of log10(width) against log10(depth) per condition at λ = `lambda`.
void write_plot(const std::filesystem::path& path, const Experiment& e, const std::string& scene,
                double lambda, const std::vector<const ManifestEntry*>& entries) {
  LinePlot plot;
  plot.title =
      e.name + ", " + scene + ": halo width against eye depth at lambda " + format_value(lambda);
  plot.x_label = "log10 eye depth (world units)";
  plot.y_label = "log10 halo width (px, along the edge's normal)";
  plot.width = 960;
  ConditionLines lines(e, plot);
  for (const ManifestEntry* s : entries) {
    if (s->scene != scene || s->lambda != lambda) continue;
    PlotSeries& series = lines.line_of(*s);
    series.points = true;
    const auto& h = s->extra["halo_widths"];
    for (size_t i = 0; i < h["depth"].size(); ++i) {
      series.x.push_back(std::log10(h["depth"][i].get<double>()));
      series.y.push_back(std::log10(h["width_px"][i].get<double>()));
    }
    const auto& slope = s->extra["depth_slope"];
    series.label +=
        slope.is_null() ? " (no slope)" : " (slope " + format_value(slope.get<double>()) + ")";
  }
  lines.fit_legend();
  plot.write(path);
}

}  // namespace

void write_depth_scale_figures(const Experiment& e, const std::filesystem::path& dir,
                               const Manifest& manifest) {
  std::vector<const ManifestEntry*> entries;
  for (const ManifestEntry& s : manifest.stimuli)
    if (s.extra.contains("halo_widths") && !s.extra["halo_widths"]["depth"].empty())
      entries.push_back(&s);
  if (entries.empty()) return;
  write_table(dir / "scale-against-depth.csv", e, entries);
  double lambda = 0;
  for (const ManifestEntry* s : entries)
    lambda = std::abs(s->lambda) > std::abs(lambda) ? s->lambda : lambda;
  for (const ExperimentScene& scene : e.scenes)
    if (!scene.probe_edges_x.empty())
      write_plot(dir / ("scale-against-depth-" + scene.name + ".svg"), e, scene.name, lambda,
                 entries);
}

}  // namespace countershade
