#include "figures/flicker_figures.h"

#include <algorithm>
#include <sstream>

#include "core/atomic_file.h"
#include "core/number_format.h"
#include "core/svg_plot.h"
#include "figures/condition_lines.h"
#include "measures/perspective_coherence.h"

namespace countershade {
namespace {

double flicker_of(const ManifestEntry& s) { return s.extra["flicker"].get<double>(); }

void write_table(const std::filesystem::path& path, const Experiment& e,
                 const std::vector<const ManifestEntry*>& entries) {
  std::ostringstream csv;
  csv << "scene,condition,lambda,frame,flicker_lstar,pixels,flicker_stable_lstar,stable_pixels,"
         "mask_flicker_lstar,"
         "mask_pixels\n";
  for (const ManifestEntry* s : entries)
    csv << condition_columns(e, *s) << s->frame->index << ',' << format_value(flicker_of(*s)) << ','
        << s->extra.value("flicker_pixels", 0) << ','
        << optional_figure_columns(*s, "flicker_stable") << ','
        << optional_figure_columns(*s, "mask_flicker") << '\n';
  write_text_atomically(path, csv.str());
}

// Which figure a plot shows: the flicker (with the plain render's own reprojection error), or the
// stable flicker (enhanced frames only).
struct FlickerFigure {
  const char* key;
  std::string title, y_label;
  bool per_lambda = true;  // false: the same at every λ (the title names none)
};

// The masks' flicker: one plot per scene, since a mask does not depend on λ.
const FlickerFigure kMaskFigure{"mask_flicker",
                                "mask flicker (the low-pass signal M; the same at every lambda)",
                                "RMS change of M per frame (L*)", false};

FlickerFigure flicker_figure(bool stable) {
  if (!stable) return {"flicker", "flicker", "RMS change of enhanced minus plain L* per frame"};
  return {"flicker_stable", "stable flicker",
          "the same RMS where the plain L* reprojects within " + format_value(kStableTolerance) +
              " L*"};
}

// One line per condition at λ index `l` against frame.
void write_plot(const std::filesystem::path& path, const Experiment& e, const std::string& scene,
                int l, const std::vector<const ManifestEntry*>& entries,
                const FlickerFigure& figure) {
  LinePlot plot;
  plot.title = e.name + ", " + scene + ": " + figure.title;
  if (figure.per_lambda) plot.title += " at lambda " + format_value(e.lambda.value(l));
  plot.x_label = "frame";
  plot.y_label = figure.y_label;
  plot.width = 960;
  ConditionLines lines(e, plot);
  for (const ManifestEntry* s : entries) {
    if (s->scene != scene || (!s->is_reference() && s->lambda_index != l) ||
        !s->extra.contains(figure.key))
      continue;
    PlotSeries& series = lines.line_of(*s);
    series.x.push_back(s->frame->index);
    series.y.push_back(s->extra[figure.key].get<double>());
  }
  lines.fit_legend();
  plot.write(path);
}

// The mask flicker of every condition with a mask, read at the first nonzero λ (every λ's entry
// holds the same figure); none where no condition has a mask.
void write_mask_plot(const std::filesystem::path& dir, const Experiment& e,
                     const std::string& scene, const std::vector<const ManifestEntry*>& entries) {
  int first = -1;
  for (int l = 0; l < e.lambda.count() && first < 0; ++l)
    if (e.lambda.value(l) != 0) first = l;
  const bool any = std::any_of(entries.begin(), entries.end(), [&](const ManifestEntry* s) {
    return s->scene == scene && s->extra.contains(kMaskFigure.key);
  });
  if (first >= 0 && any)
    write_plot(dir / ("flicker-mask-" + scene + ".svg"), e, scene, first, entries, kMaskFigure);
}

}  // namespace

void write_flicker_figures(const Experiment& e, const std::filesystem::path& dir,
                           const Manifest& manifest) {
  std::vector<const ManifestEntry*> entries;  // in file order: frames ascending within a sequence
  for (const ManifestEntry& s : manifest.stimuli)
    if (s.frame && s.extra.contains("flicker")) entries.push_back(&s);
  if (entries.empty()) return;
  write_table(dir / "flicker.csv", e, entries);
  for (const ExperimentScene& scene : e.scenes) {
    if (!scene.is_sequence()) continue;
    for (int l = 0; l < e.lambda.count(); ++l)
      if (e.lambda.value(l) != 0)
        for (bool stable : {false, true}) {
          const std::string name = std::string(stable ? "flicker-stable-" : "flicker-") +
                                   scene.name + "-lambda-" + format_value(e.lambda.value(l)) +
                                   ".svg";
          write_plot(dir / name, e, scene.name, l, entries, flicker_figure(stable));
        }
    write_mask_plot(dir, e, scene.name, entries);
  }
}

}  // namespace countershade
