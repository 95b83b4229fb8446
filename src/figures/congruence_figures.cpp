#include "figures/congruence_figures.h"

#include <algorithm>
#include <map>
#include <numeric>
#include <sstream>

#include "core/atomic_file.h"
#include "core/number_format.h"
#include "core/svg_plot.h"
#include "figures/contact_sheet.h"

namespace countershade {
namespace {

// One curve of the figure: a condition (the plain render, or a method's label at one σ) with its
// stimulus at the strongest λ for every scene, in the experiment's scene order.
struct Condition {
  std::string name;
  std::vector<const ManifestEntry*> per_scene;
};

std::string condition_name(const ManifestEntry& s, const ExperimentMethod& m) {
  return m.sigmas.size() > 1 ? m.label + " sigma " + format_value(*s.sigma) : m.label;
}

// The conditions, or none when any stimulus the figure needs has no score.
std::vector<Condition> scored_conditions(const Experiment& e, const Manifest& manifest) {
  std::map<std::string, size_t> scene_index, label_index;
  for (size_t i = 0; i < e.scenes.size(); ++i) scene_index[e.scenes[i].name] = i;
  for (size_t i = 0; i < e.methods.size(); ++i) label_index[e.methods[i].label] = i;
  std::vector<Condition> conditions{
      {"plain", std::vector<const ManifestEntry*>(e.scenes.size(), nullptr)}};
  std::map<std::string, size_t> index_of{{"plain", 0}};
  const int strongest = e.lambda.count() - 1;
  for (const ManifestEntry& s : manifest.stimuli) {
    const bool reference = s.is_reference();
    if (!reference && s.lambda_index != strongest) continue;
    const std::string name =
        reference ? "plain" : condition_name(s, e.methods[label_index.at(s.label)]);
    auto [it, added] = index_of.emplace(name, conditions.size());
    if (added)
      conditions.push_back({name, std::vector<const ManifestEntry*>(e.scenes.size(), nullptr)});
    conditions[it->second].per_scene[scene_index.at(s.scene)] = &s;
  }
  for (const Condition& c : conditions)
    for (const ManifestEntry* s : c.per_scene)
      if (s && !s->extra.contains("congruence")) return {};
  return conditions;
}

double score_of(const ManifestEntry& s) { return s.extra["congruence"].get<double>(); }

void write_table(const std::filesystem::path& path, const Experiment& e,
                 const std::vector<Condition>& conditions) {
  std::ostringstream csv;
  csv << "scene_index,scene,condition,lambda,congruence\n";
  for (const Condition& c : conditions)
    for (size_t i = 0; i < c.per_scene.size(); ++i)
      if (const ManifestEntry* s = c.per_scene[i])
        csv << i + 1 << ',' << e.scenes[i].name << ',' << c.name << ',' << format_value(s->lambda)
            << ',' << format_value(score_of(*s)) << '\n';
  write_text_atomically(path, csv.str());
}

// The scores of the scenes `scenes` (indices in the experiment's order) against their position
// in that list, one line per condition.
void write_plot(const std::filesystem::path& path, const std::string& title, bool swept,
                const std::vector<size_t>& scenes, const std::vector<Condition>& conditions) {
  LinePlot plot;
  plot.title = title;
  plot.x_label = swept ? "light direction: by elevation, then azimuth (names in congruence.csv)"
                       : "scene (in the experiment's order; names in congruence.csv)";
  plot.y_label = "congruence";
  plot.width = 900;
  for (size_t k = 0; k < conditions.size(); ++k) {
    PlotSeries series{conditions[k].name, {}, {}, plot_color(k), k == 0};
    for (size_t i = 0; i < scenes.size(); ++i)
      if (const ManifestEntry* s = conditions[k].per_scene[scenes[i]])
        series.x.push_back(double(i + 1)), series.y.push_back(score_of(*s));
    plot.series.push_back(series);
  }
  plot.write(path);
}

// congruence.svg over every scene; where several scene entries each sweep the light, also one
// figure per entry, its directions numbered from 1 (congruence-NAME.svg).
void write_plots(const std::filesystem::path& dir, const Experiment& e,
                 const std::vector<Condition>& conditions) {
  const std::string at = " at lambda " + format_value(e.lambda.max);
  std::vector<size_t> all(e.scenes.size());
  std::iota(all.begin(), all.end(), size_t(0));
  std::map<std::string, std::vector<size_t>> swept;
  for (size_t i : all)
    if (e.scenes[i].light) swept[e.scenes[i].swept_from].push_back(i);
  const bool all_swept = std::all_of(e.scenes.begin(), e.scenes.end(),
                                     [](const ExperimentScene& s) { return s.light.has_value(); });
  write_plot(dir / "congruence.svg", e.name + ": congruence per scene" + at, all_swept, all,
             conditions);
  if (swept.size() < 2) return;
  for (const auto& [name, scenes] : swept)
    write_plot(dir / ("congruence-" + name + ".svg"), e.name + ": congruence of " + name + at, true,
               scenes, conditions);
}

// One sheet per condition: each scene's stimulus beside its score map.
void write_sheet(const std::filesystem::path& dir, const Experiment& e, const Condition& c) {
  std::vector<std::string> rows;
  std::vector<std::vector<ContactCell>> cells;
  for (size_t i = 0; i < c.per_scene.size(); ++i) {
    const ManifestEntry* s = c.per_scene[i];
    if (!s) continue;
    rows.push_back(e.scenes[i].name);
    const std::string score = "congruence " + format_value(round_to(score_of(*s), 3));
    cells.push_back({{dir / s->file, ""},
                     {dir / s->extra["congruence_map"]["file"].get<std::string>(), score}});
  }
  std::string file = c.name;
  for (char& ch : file)
    if (ch == ' ') ch = '-';
  write_contact_sheet(dir / "contact-sheets" / ("congruence-" + file + ".png"),
                      c.name + ": congruence", rows, {"render", "map (0 blue, 1 yellow)"}, cells,
                      240);
}

}  // namespace

void write_congruence_figures(const Experiment& e, const std::filesystem::path& dir,
                              const Manifest& manifest, bool sheets) {
  const std::vector<Condition> conditions = scored_conditions(e, manifest);
  if (conditions.empty()) return;
  write_table(dir / "congruence.csv", e, conditions);
  write_plots(dir, e, conditions);
  if (!sheets) return;
  std::filesystem::create_directories(dir / "contact-sheets");
  for (const Condition& c : conditions) write_sheet(dir, e, c);
}

}  // namespace countershade
