#include "stimuli/coherence_figures.h"

#include <map>
#include <sstream>

#include "core/atomic_file.h"
#include "core/number_format.h"
#include "core/svg_plot.h"

namespace countershade {
namespace {

double coherence_of(const ManifestEntry& s) { return s.extra["coherence"].get<double>(); }

std::string condition_of(const Experiment& e, const ManifestEntry& s) {
  if (s.is_reference()) return "plain";
  for (const ExperimentMethod& m : e.methods)
    if (m.label == s.label) return m.sigmas.size() > 1 ? m.label + " sigma " + format_value(*s.sigma) : m.label;
  return s.label;
}

void write_table(const std::filesystem::path& path, const Experiment& e, const std::vector<const ManifestEntry*>& entries) {
  std::ostringstream csv;
  csv << "scene,condition,lambda,coherence_rms_lstar,pixels\n";
  for (const ManifestEntry* s : entries)
    csv << s->scene << ',' << condition_of(e, *s) << ',' << (s->is_reference() ? "" : format_value(s->lambda)) << ','
        << format_value(coherence_of(*s)) << ',' << s->extra.value("coherence_pixels", 0) << '\n';
  write_text_atomically(path, csv.str());
}

// One line per condition: a colour per method label, solid for its first σ and dashed for the
// others; the plain render's reprojection error grey and dashed across the grid.
void write_plot(const std::filesystem::path& path, const Experiment& e, const std::string& scene,
                const std::vector<const ManifestEntry*>& entries) {
  LinePlot plot;
  plot.title = e.name + ", " + scene + ": change of the enhancement under a " +
               format_value(100 * *e.coherence_dolly) + " % dolly";
  plot.x_label = "lambda";
  plot.y_label = "RMS change of enhanced minus plain L*";
  plot.width = 960;
  std::map<std::string, size_t> index_of, label_colour, sigmas_of_label;
  for (const ManifestEntry* s : entries) {
    if (s->scene != scene) continue;
    auto [it, added] = index_of.emplace(condition_of(e, *s), plot.series.size());
    if (added) {
      const bool plain = s->is_reference();
      const size_t colour = label_colour.emplace(s->label, label_colour.size()).first->second;
      const size_t sigma = plain ? 0 : sigmas_of_label[s->label]++;
      plot.series.push_back({it->first, {}, {}, plain ? "#777777" : plot_color(colour), plain || sigma > 0});
    }
    PlotSeries& series = plot.series[it->second];
    if (s->is_reference()) {
      series.x = {e.lambda.min, e.lambda.max};
      series.y = {coherence_of(*s), coherence_of(*s)};
    } else {
      series.x.push_back(s->lambda);
      series.y.push_back(coherence_of(*s));
    }
  }
  plot.height = std::max(400, 110 + 18 * int(plot.series.size()));  // the legend fits
  plot.write(path);
}

}  // namespace

void write_coherence_figures(const Experiment& e, const std::filesystem::path& dir, const Manifest& manifest) {
  std::vector<const ManifestEntry*> entries;
  for (const ManifestEntry& s : manifest.stimuli)
    if (s.extra.contains("coherence")) entries.push_back(&s);
  if (entries.empty() || !e.coherence_dolly) return;
  write_table(dir / "coherence.csv", e, entries);
  for (const ExperimentScene& scene : e.scenes) write_plot(dir / ("coherence-" + scene.name + ".svg"), e, scene.name, entries);
}

}  // namespace countershade
