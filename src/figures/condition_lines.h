#pragma once
// Figures of a measure recorded per stimulus (coherence, flicker): how they name a condition, its
// columns in a table, and its line in a plot.

#include <map>
#include <string>

#include "core/svg_plot.h"
#include "formats/manifest.h"
#include "stimuli/experiment.h"

namespace countershade {

// "plain" for the reference, else the method's label, with its σ where the method has several.
std::string condition_name(const Experiment& experiment, const ManifestEntry& entry);

// "scene,condition,lambda," (λ empty for the reference): the first columns of a table's row.
std::string condition_columns(const Experiment& experiment, const ManifestEntry& entry);

// "value,pixels" of a figure the entry may lack (`key` and `key`_pixels in its extra fields), or
// "," without it: the last columns of a table's row for the stable figures.
std::string optional_figure_columns(const ManifestEntry& entry, const std::string& key);

// The lines of a plot with one line per condition: a colour per method (by its place in the
// experiment, the same in every plot), solid for its first σ and dashed for the others; the plain
// render grey and dashed.
class ConditionLines {
 public:
  ConditionLines(const Experiment& experiment, LinePlot& plot) : e_(experiment), plot_(plot) {}
  PlotSeries& line_of(const ManifestEntry& entry);  // added on first use
  void fit_legend();                                // makes the plot tall enough for its legend

 private:
  size_t method_index(const std::string& label) const;

  const Experiment& e_;
  LinePlot& plot_;
  std::map<std::string, size_t> index_of_, label_colour_, sigmas_of_label_;
};

}  // namespace countershade
