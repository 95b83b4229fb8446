#include "figures/condition_lines.h"

#include <algorithm>

#include "core/number_format.h"

namespace countershade {

std::string condition_name(const Experiment& e, const ManifestEntry& s) {
  if (s.is_reference()) return "plain";
  for (const ExperimentMethod& m : e.methods)
    if (m.label == s.label)
      return m.sigmas.size() > 1 ? m.label + " sigma " + format_value(*s.sigma) : m.label;
  return s.label;
}

std::string condition_columns(const Experiment& e, const ManifestEntry& s) {
  return s.scene + ',' + condition_name(e, s) + ',' +
         (s.is_reference() ? "" : format_value(s.lambda)) + ',';
}

std::string optional_figure_columns(const ManifestEntry& s, const std::string& key) {
  if (!s.extra.contains(key)) return ",";
  return format_value(s.extra[key].get<double>()) + ',' +
         std::to_string(s.extra.value(key + "_pixels", size_t(0)));
}

// The method's place in the experiment, so that a method keeps its colour in every plot of a set
// whatever lines a plot holds (after the known methods: the order of first use).
size_t ConditionLines::method_index(const std::string& label) const {
  for (size_t m = 0; m < e_.methods.size(); ++m)
    if (e_.methods[m].label == label) return m;
  return e_.methods.size() + label_colour_.size();
}

PlotSeries& ConditionLines::line_of(const ManifestEntry& s) {
  auto [it, added] = index_of_.emplace(condition_name(e_, s), plot_.series.size());
  if (added) {
    const bool plain = s.is_reference();
    const size_t colour = label_colour_.emplace(s.label, method_index(s.label)).first->second;
    const size_t sigma = plain ? 0 : sigmas_of_label_[s.label]++;
    plot_.series.push_back(
        {it->first, {}, {}, plain ? "#777777" : plot_color(colour), plain || sigma > 0});
  }
  return plot_.series[it->second];
}

void ConditionLines::fit_legend() {
  plot_.height = std::max(plot_.height, 110 + 18 * int(plot_.series.size()));
}

}  // namespace countershade
