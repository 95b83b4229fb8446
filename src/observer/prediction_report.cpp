#include "observer/prediction_report.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/atomic_file.h"
#include "core/number_format.h"
#include "core/svg_plot.h"
#include "core/xml.h"
#include "formats/responses.h"

namespace countershade::observer {

std::string rounded(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", v);
  return text;
}

namespace {

std::string optional_value(const std::optional<double>& v) { return v ? rounded(*v) : ""; }

std::vector<std::string> key_fields(const ConditionPrediction& c) {
  return {c.scene, c.method, format_value(c.sigma)};
}

std::string condition_title(const ConditionPrediction& c) {
  return c.scene + ": " + c.method + ", σ " + format_value(c.sigma);
}

// JND against λ, a marker at every grid value, the three levels dashed.
std::string condition_plot(const ConditionPrediction& c) {
  LinePlot plot;
  plot.title = condition_title(c);
  plot.x_label = "λ";
  plot.y_label = "predicted JND";
  plot.log_y = true;  // responses span decades; the levels 1, 2 and 4 JND are equally spaced
  plot.width = 420;
  plot.height = 260;
  plot.series.push_back({"", c.lambda, c.jnd, plot_color(0)});
  plot.series.push_back({"grid", c.lambda, c.jnd, plot_color(0), false, true});
  const double left = c.lambda.front(), right = c.lambda.back();
  for (size_t l = 0; l < kPredictionLevels.size(); ++l) {
    const double level = kPredictionLevels[l];
    plot.series.push_back(
        {format_value(level) + " JND", {left, right}, {level, level}, plot_color(l + 1), true});
  }
  return plot.to_svg();
}

// The scenes in the prediction's order.
std::vector<std::string> scenes_of(const SetPrediction& prediction) {
  std::vector<std::string> scenes;
  for (const auto& c : prediction.conditions)
    if (std::find(scenes.begin(), scenes.end(), c.scene) == scenes.end()) scenes.push_back(c.scene);
  return scenes;
}

// Every condition of a scene that responds, JND against λ on one log axis, the levels dashed.
std::string scene_plot(const SetPrediction& prediction, const std::string& scene) {
  LinePlot plot;
  plot.title = scene + ": predicted JND against λ";
  plot.x_label = "λ";
  plot.y_label = "predicted JND";
  plot.log_y = true;
  plot.width = 640;
  plot.height = 360;
  double left = INFINITY, right = -INFINITY;
  size_t k = 0;
  for (const auto& c : prediction.conditions) {
    if (c.scene != scene || c.lambda.empty() || c.jnd_at_lambda_max() <= 0) continue;
    plot.series.push_back(
        {c.method + " σ " + format_value(c.sigma), c.lambda, c.jnd, plot_color(k++)});
    left = std::min(left, c.lambda.front());
    right = std::max(right, c.lambda.back());
  }
  if (plot.series.empty()) return "";
  for (double level : kPredictionLevels)
    plot.series.push_back({"", {left, right}, {level, level}, "#888888", true});
  return plot.to_svg();
}

// A file name from a scene's name: letters, digits, '.', '_' and '-' survive, so that text from a
// manifest never leaves the output folder.
std::string safe_file_name(const std::string& name) {
  std::string out;
  for (char ch : name)
    out += std::isalnum(static_cast<unsigned char>(ch)) || ch == '.' || ch == '_' || ch == '-'
               ? ch
               : '_';
  return out.empty() || out[0] == '.' ? "_" + out : out;
}

std::string table_html(const SetPrediction& prediction) {
  std::ostringstream h;
  h << "<table><tr><th>scene</th><th>condition</th><th>σ</th><th>λ at 1 JND</th>"
       "<th>λ at 2 JND</th><th>λ at 4 JND</th><th>JND at the largest λ</th></tr>\n";
  for (const auto& c : prediction.conditions) {
    h << "<tr><td>" << xml_escape(c.scene) << "</td><td>" << xml_escape(c.method) << "</td><td>"
      << format_value(c.sigma) << "</td>";
    for (const auto& v : c.lambda_at)
      h << "<td>" << (v ? rounded(*v) : "beyond the grid") << "</td>";
    h << "<td>" << rounded(c.jnd_at_lambda_max()) << "</td></tr>\n";
  }
  h << "</table>\n";
  return h.str();
}

}  // namespace

std::string predicted_thresholds_csv(const SetPrediction& prediction) {
  std::string out = csv_line({"scene", "method", "sigma", "lambda_1jnd", "lambda_2jnd",
                              "lambda_4jnd", "jnd_at_lambda_max"});
  for (const auto& c : prediction.conditions) {
    std::vector<std::string> row = key_fields(c);
    for (const auto& v : c.lambda_at) row.push_back(optional_value(v));
    row.push_back(rounded(c.jnd_at_lambda_max()));
    out += csv_line(row);
  }
  return out;
}

std::string predicted_jnd_csv(const SetPrediction& prediction) {
  std::string out = csv_line({"scene", "method", "sigma", "lambda", "jnd"});
  for (const auto& c : prediction.conditions)
    for (size_t i = 0; i < c.lambda.size(); ++i) {
      std::vector<std::string> row = key_fields(c);
      row.push_back(format_value(c.lambda[i]));
      row.push_back(rounded(c.jnd[i]));
      out += csv_line(row);
    }
  return out;
}

namespace {

// The page's head: the set, how it was seen, what the levels mean and what the model cannot do.
void report_head(std::ostringstream& h, const PredictionContext& context) {
  h << "<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>Predicted visibility of "
    << xml_escape(context.set_name)
    << "</title><style>body{font-family:sans-serif;margin:1.5em}table{border-collapse:collapse}"
       "td,th{border:1px solid #ccc;padding:2px 8px;text-align:right}svg{margin:4px}"
       "</style></head><body>\n<h1>Predicted visibility: "
    << xml_escape(context.set_name) << "</h1>\n<p>" << xml_escape(context.manifest) << ", seen at "
    << rounded(context.ppd) << " pixels per degree on " << xml_escape(context.display)
    << "; the detection model of docs/observer.md (gain " << format_value(context.model.gain)
    << ", β " << format_value(context.model.beta)
    << "). 1 JND is the threshold (84 % correct in 2IFC); 2 JND is near the enhancement "
       "observers preferred and 4 JND near the most they tolerated (Ritschel et al. 2008).</p>\n"
       "<p>A prediction to design a grid with, not a measurement: the model is foveal, static "
       "and achromatic, predicts the detection of a difference and not preference, and is least "
       "certain for large, complex images.</p>\n";
}

// One plot per condition, or one line for a condition that responds at no λ (a control).
void condition_sections(std::ostringstream& h, const SetPrediction& prediction) {
  h << "<h2>Each condition, its grid marked</h2>\n";
  for (const auto& c : prediction.conditions) {
    const bool responds = std::any_of(c.jnd.begin(), c.jnd.end(), [](double v) { return v > 0; });
    if (responds)
      h << condition_plot(c) << "\n";
    else
      h << "<p>" << xml_escape(condition_title(c))
        << ": no response at any λ (every image equals the reference).</p>\n";
  }
}

}  // namespace

std::string prediction_report_html(const SetPrediction& prediction,
                                   const PredictionContext& context) {
  std::ostringstream h;
  report_head(h, context);
  if (prediction.sequence_conditions_skipped > 0)
    h << "<p>" << prediction.sequence_conditions_skipped
      << " sequence condition(s) left out: the model is static.</p>\n";
  if (prediction.conditions.empty()) {
    h << "<p>The set has no still condition to predict.</p></body></html>\n";
    return h.str();
  }
  h << table_html(prediction);
  for (const auto& scene : scenes_of(prediction)) h << scene_plot(prediction, scene) << "\n";
  condition_sections(h, prediction);
  h << "<p><small>Every image's response: predicted_jnd.csv; the table: "
       "predicted_thresholds.csv.</small></p></body></html>\n";
  return h.str();
}

void write_prediction(const std::filesystem::path& dir, const SetPrediction& prediction,
                      const PredictionContext& context) {
  std::filesystem::create_directories(dir);
  write_text_atomically(dir / "predicted_thresholds.csv", predicted_thresholds_csv(prediction));
  write_text_atomically(dir / "predicted_jnd.csv", predicted_jnd_csv(prediction));
  write_text_atomically(dir / "report.html", prediction_report_html(prediction, context));
  for (const auto& scene : scenes_of(prediction)) {
    const std::string svg = scene_plot(prediction, scene);
    if (!svg.empty()) write_text_atomically(dir / ("jnd-" + safe_file_name(scene) + ".svg"), svg);
  }
}

}  // namespace countershade::observer
