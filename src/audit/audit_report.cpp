#include "audit/audit_report.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/atomic_file.h"
#include "core/number_format.h"
#include "core/svg_plot.h"
#include "core/xml.h"
#include "figures/contact_sheet.h"
#include "formats/responses.h"

namespace countershade {
namespace {

using json = nlohmann::ordered_json;

json optional_number(const std::optional<double>& v) { return v ? json(*v) : json(nullptr); }

// `luminance`: the set has a scene on a calibrated display, so every row gets the column;
// `quantisation`: the set is 16-bit, so every row gets the share 8 bits would lose.
json stimulus_json(const StimulusAudit& s, bool luminance, bool quantisation) {
  json out = {{"file", s.file},
              {"scene", s.scene},
              {"condition", s.reference ? "reference" : s.condition},
              {"sigma", s.sigma},
              {"lambda", s.lambda},
              {"mean_lightness", s.mean_lightness},
              {"rms_contrast", s.rms_contrast},
              {"clipped_fraction", s.clipped_fraction},
              {"delta_e_mean", s.delta_e_mean},
              {"delta_e_p99", s.delta_e_p99},
              {"changed_fraction", s.changed_fraction},
              {"noise_rms", optional_number(s.noise_rms)},
              {"noise_p99", optional_number(s.noise_p99)}};
  if (luminance) out["mean_luminance_cd_m2"] = optional_number(s.mean_luminance_cd_m2);
  if (quantisation) out["quantisation_loss"] = optional_number(s.quantisation_loss);
  return out;
}

json report_json(const AuditReport& r) {
  json out = {{"manifest", r.manifest.string()}, {"set", r.set_name}, {"failed", r.failed()}};
  out["limits"] = {{"max_drift", r.limits.max_drift}, {"max_clipped", r.limits.max_clipped}};
  if (r.limits.screen_width)
    out["limits"]["screen"] = {{"width", *r.limits.screen_width},
                               {"height", *r.limits.screen_height}};
  out["checks"] = json::array();
  for (const auto& c : r.checks)
    out["checks"].push_back({{"check", c.check},
                             {"scene", c.scene},
                             {"condition", c.condition},
                             {"passed", c.passed},
                             {"detail", c.detail}});
  out["stimuli"] = json::array();
  const bool luminance =
      std::any_of(r.stimuli.begin(), r.stimuli.end(),
                  [](const StimulusAudit& s) { return s.mean_luminance_cd_m2.has_value(); });
  const bool quantisation =
      std::any_of(r.stimuli.begin(), r.stimuli.end(),
                  [](const StimulusAudit& s) { return s.quantisation_loss.has_value(); });
  for (const auto& s : r.stimuli)
    out["stimuli"].push_back(stimulus_json(s, luminance, quantisation));
  out["notes"] = r.notes;
  return out;
}

// One row per stimulus with the columns of stimulus_json.
std::string stimuli_csv(const json& stimuli) {
  std::ostringstream csv;
  csv.precision(10);
  bool header = true;
  for (const auto& s : stimuli) {
    if (header) {
      for (auto it = s.begin(); it != s.end(); ++it)
        csv << (it == s.begin() ? "" : ",") << it.key();
      csv << "\n";
      header = false;
    }
    for (auto it = s.begin(); it != s.end(); ++it) {
      csv << (it == s.begin() ? "" : ",");
      if (it->is_string())
        csv << csv_field(it->get<std::string>());
      else if (!it->is_null())
        csv << it->get<double>();
    }
    csv << "\n";
  }
  return csv.str();
}

std::string checks_csv(const AuditReport& r) {
  std::ostringstream csv;
  csv << "check,scene,condition,passed,detail\n";
  for (const auto& c : r.checks)
    csv << csv_field(c.check) << "," << csv_field(c.scene) << "," << csv_field(c.condition) << ","
        << (c.passed ? "true" : "false") << "," << csv_field(c.detail) << "\n";
  return csv.str();
}

// A measure's limit, drawn dashed: at +value, and at −value too for a two-sided one (drift).
struct PlotLimit {
  double value;
  bool two_sided = false;
};

// One measure of a condition against λ, with its limit where there is one. A sequence plots its
// worst frame at each λ (the value of largest magnitude).
std::string measure_plot(const AuditCondition& c, const std::string& title, const std::string& unit,
                         double (*value)(const StimulusAudit&, const StimulusAudit&),
                         std::optional<PlotLimit> limit) {
  LinePlot plot;
  plot.title = title;
  plot.x_label = "λ";
  plot.y_label = unit;
  plot.width = 340;
  plot.height = 210;
  PlotSeries series;
  series.label = "";
  series.color = plot_color(0);
  for (const auto* s : c.stimuli) {
    const double v = value(*s, *c.reference);
    if (std::isnan(v)) continue;  // no value at this λ (e.g. nothing changed to lose)
    if (!series.x.empty() && series.x.back() == s->lambda) {  // another frame at this λ
      if (std::abs(v) > std::abs(series.y.back())) series.y.back() = v;
      continue;
    }
    series.x.push_back(s->lambda);
    series.y.push_back(v);
  }
  plot.series.push_back(series);
  if (limit && !series.x.empty())
    for (double sign : {1.0, -1.0}) {
      if (sign < 0 && !limit->two_sided) continue;
      const double y = sign * limit->value;
      plot.series.push_back(
          {sign > 0 ? "limit" : "", {series.x.front(), series.x.back()}, {y, y}, "#D55E00", true});
    }
  return plot.to_svg();
}

std::string condition_plots(const AuditCondition& c, const AuditLimits& limits) {
  std::string out;
  out += measure_plot(
      c, "mean L* drift from the reference", "ΔL*",
      [](const StimulusAudit& s, const StimulusAudit&) { return s.drift; },
      PlotLimit{limits.max_drift, true});
  out += measure_plot(
      c, "RMS contrast (SD of L*)", "L*",
      [](const StimulusAudit& s, const StimulusAudit&) { return s.rms_contrast; }, std::nullopt);
  out += measure_plot(
      c, "clipped pixels", "%",
      [](const StimulusAudit& s, const StimulusAudit&) { return 100 * s.clipped_fraction; },
      PlotLimit{100 * limits.max_clipped});
  out += measure_plot(
      c, "CIEDE2000 to the reference, mean", "ΔE00",
      [](const StimulusAudit& s, const StimulusAudit&) { return s.delta_e_mean; }, std::nullopt);
  out += measure_plot(
      c, "CIEDE2000 to the reference, p99", "ΔE00",
      [](const StimulusAudit& s, const StimulusAudit&) { return s.delta_e_p99; }, std::nullopt);
  out += measure_plot(
      c, "pixels changed", "%",
      [](const StimulusAudit& s, const StimulusAudit&) { return 100 * s.changed_fraction; },
      std::nullopt);
  if (std::any_of(c.stimuli.begin(), c.stimuli.end(),
                  [](const StimulusAudit* s) { return s->quantisation_loss.has_value(); }))
    out += measure_plot(
        c, "change lost at 8 bits", "%",
        [](const StimulusAudit& s, const StimulusAudit&) {
          return 100 * s.quantisation_loss.value_or(NAN);
        },
        PlotLimit{100 * kQuantisationWarning});
  if (c.stimuli.front()->noise_rms)
    out += measure_plot(
        c, "estimated sampling noise (RMS)", "L*",
        [](const StimulusAudit& s, const StimulusAudit&) { return s.noise_rms.value_or(0.0); },
        std::nullopt);
  return out;
}

// The reference, the middle and the strongest λ of a condition, small.
std::string thumbnail_strip(const AuditCondition& c, const std::filesystem::path& set_dir,
                            const std::filesystem::path& dir, size_t index) {
  const std::string name = "thumbnails/condition-" + std::to_string(index) + ".png";
  const StimulusAudit* picks[3] = {c.reference, c.stimuli[c.stimuli.size() / 2], c.stimuli.back()};
  std::vector<std::string> columns;
  std::vector<ContactCell> row;
  for (const auto* s : picks) {
    columns.push_back(s->reference ? "reference" : "λ = " + format_value(s->lambda));
    row.push_back({resolve_in_set(set_dir, s->file), ""});
  }
  write_contact_sheet(dir / name, c.scene + " - " + c.name, {""}, columns, {row}, 160);
  return name;
}

std::string checks_table(const AuditReport& r) {
  std::ostringstream h;
  h << "<table><tr><th>scene</th><th>condition</th><th>check</th><th>outcome</th><th>detail</th></"
       "tr>\n";
  for (const auto& c : r.checks)
    h << "<tr class=\"" << (c.passed ? "pass" : "fail") << "\"><td>" << xml_escape(c.scene)
      << "</td><td>" << xml_escape(c.condition) << "</td><td>" << xml_escape(c.check) << "</td><td>"
      << (c.passed ? "pass" : "FAIL") << "</td><td>" << xml_escape(c.detail) << "</td></tr>\n";
  h << "</table>\n";
  return h.str();
}

std::string report_html(const AuditReport& r, const std::filesystem::path& dir) {
  std::ostringstream h;
  h << "<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>Audit of "
    << xml_escape(r.set_name)
    << "</title><style>body{font-family:sans-serif;margin:2em} table{border-collapse:collapse} "
       "td,th{border:1px solid "
       "#ccc;padding:3px 8px} tr.fail{background:#f8d0c8} tr.pass{background:#e4f3e4} "
       "svg{margin:4px}</style></head><body>\n"
    << "<h1>Stimulus audit: " << xml_escape(r.set_name) << "</h1>\n<p>"
    << xml_escape(r.manifest.string()) << ": " << xml_escape(r.summary())
    << ". Limits: mean L* drift ≤ " << format_value(r.limits.max_drift) << " L*, clipped pixels ≤ "
    << format_value(100 * r.limits.max_clipped) << " %.</p>\n";
  for (const auto& n : r.notes) h << "<p><b>Note:</b> " << xml_escape(n) << "</p>\n";
  h << "<h2>Checks</h2>\n" << checks_table(r);
  const std::filesystem::path set_dir = r.manifest.parent_path();
  const auto conditions = audit_conditions(r);
  for (size_t i = 0; i < conditions.size(); ++i) {
    const auto& c = conditions[i];
    h << "<h2>" << xml_escape(c.scene + ": " + c.name) << "</h2>\n<img src=\""
      << thumbnail_strip(c, set_dir, dir, i) << "\"><br>\n"
      << condition_plots(c, r.limits) << "\n";
  }
  h << "<p><small>Generated by countershade audit. Per-stimulus values: audit.csv, "
       "audit.json.</small></p></body></html>\n";
  return h.str();
}

}  // namespace

void write_audit_report(const AuditReport& report, const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir / "thumbnails");
  const json j = report_json(report);
  write_text_atomically(dir / "audit.json", j.dump(2) + "\n");
  write_text_atomically(dir / "audit.csv", stimuli_csv(j["stimuli"]));
  write_text_atomically(dir / "checks.csv", checks_csv(report));
  write_text_atomically(dir / "report.html", report_html(report, dir));
}

}  // namespace countershade
