#include "figures/coherence_figures.h"

#include <sstream>

#include "core/atomic_file.h"
#include "core/number_format.h"
#include "core/svg_plot.h"
#include "figures/condition_lines.h"

namespace countershade {
namespace {

double coherence_of(const ManifestEntry& s) { return s.extra["coherence"].get<double>(); }

void write_table(const std::filesystem::path& path, const Experiment& e,
                 const std::vector<const ManifestEntry*>& entries) {
  std::ostringstream csv;
  csv << "scene,condition,lambda,coherence_rms_lstar,pixels,coherence_stable_lstar,stable_pixels\n";
  for (const ManifestEntry* s : entries)
    csv << condition_columns(e, *s) << format_value(coherence_of(*s)) << ','
        << s->extra.value("coherence_pixels", 0) << ','
        << optional_figure_columns(*s, "coherence_stable") << '\n';
  write_text_atomically(path, csv.str());
}

// One line per condition against λ; the plain render's reprojection error across the grid.
void write_plot(const std::filesystem::path& path, const Experiment& e, const std::string& scene,
                const std::vector<const ManifestEntry*>& entries) {
  LinePlot plot;
  plot.title = e.name + ", " + scene + ": change of the enhancement under a " +
               format_value(100 * *e.coherence_dolly) + " % dolly";
  plot.x_label = "lambda";
  plot.y_label = "RMS change of enhanced minus plain L*";
  plot.width = 960;
  ConditionLines lines(e, plot);
  for (const ManifestEntry* s : entries) {
    if (s->scene != scene) continue;
    PlotSeries& series = lines.line_of(*s);
    if (s->is_reference()) {
      series.x = {e.lambda.min, e.lambda.max};
      series.y = {coherence_of(*s), coherence_of(*s)};
    } else {
      series.x.push_back(s->lambda);
      series.y.push_back(coherence_of(*s));
    }
  }
  lines.fit_legend();
  plot.write(path);
}

}  // namespace

void write_coherence_figures(const Experiment& e, const std::filesystem::path& dir,
                             const Manifest& manifest) {
  std::vector<const ManifestEntry*> entries;
  for (const ManifestEntry& s : manifest.stimuli)
    if (s.extra.contains("coherence")) entries.push_back(&s);
  if (entries.empty() || !e.coherence_dolly) return;
  write_table(dir / "coherence.csv", e, entries);
  for (const ExperimentScene& scene : e.scenes)
    write_plot(dir / ("coherence-" + scene.name + ".svg"), e, scene.name, entries);
}

}  // namespace countershade
