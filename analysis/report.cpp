#include "analysis/report.h"

#include <cctype>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "analysis/figures.h"
#include "analysis/html_table.h"
#include "core/atomic_file.h"
#include "core/xml.h"

namespace countershade::analysis {
namespace {

using json = nlohmann::ordered_json;

void write_text(const std::filesystem::path& path, const std::string& text) {
  write_text_atomically(path, text);
}

std::string cell(const json& v) {
  if (v.is_string()) return csv_field(v.get<std::string>());
  if (not_available(v)) return "NA";
  if (infinite(v)) return v.get<double>() > 0 ? "Inf" : "-Inf";
  std::ostringstream s;
  s.precision(15);
  if (v.is_number_float())
    s << v.get<double>();
  else
    s << v.dump();
  return s.str();
}

// A JSON array of flat objects as CSV, columns in the first row's order.
// The table's rows under a header of their keys; an empty table is the header `empty_columns`
// alone, so that a script reading it finds its columns.
std::string table_csv(const json& rows, const std::vector<std::string>& empty_columns = {}) {
  std::ostringstream out;
  std::vector<std::string> keys = empty_columns;
  if (rows.is_array() && !rows.empty()) {
    keys.clear();
    for (auto it = rows[0].begin(); it != rows[0].end(); ++it) keys.push_back(it.key());
  }
  if (keys.empty()) return "";
  for (size_t k = 0; k < keys.size(); ++k) out << (k ? "," : "") << keys[k];
  out << "\n";
  for (const auto& row : rows) {
    for (size_t k = 0; k < keys.size(); ++k)
      out << (k ? "," : "") << (row.contains(keys[k]) ? cell(row[keys[k]]) : "");
    out << "\n";
  }
  return out.str();
}

// APA style: no leading zero for values bounded by 1, "p < .001" below that.
std::string apa_unit(double v, int decimals) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(decimals);
  s << v;
  std::string text = s.str();
  if (text.rfind("0.", 0) == 0) text.erase(0, 1);
  if (text.rfind("-0.", 0) == 0) text.erase(1, 1);
  return text;
}
std::string apa_p(double p) { return p < 0.001 ? "p < .001" : "p = " + apa_unit(p, 3); }
std::string df_text(double df) {
  return std::abs(df - std::round(df)) < 1e-9 ? fixed(df, 0) : fixed(df, 2);
}

std::string anova_statement(const json& r) {
  std::string text = "F(" + df_text(r["df1"]) + ", " + df_text(r["df2"]) +
                     ") = " + fixed(r["F"], 2) + ", " + apa_p(r["p"]) +
                     ", η²G = " + apa_unit(r["ges"], 2);
  if (r.contains("gg_epsilon") && r["mauchly_p"].get<double>() < 0.05)
    text += " (sphericity violated, Mauchly W = " + apa_unit(r["mauchly_W"], 2) + ", " +
            apa_p(r["mauchly_p"]) + "; Greenhouse–Geisser ε = " + apa_unit(r["gg_epsilon"], 2) +
            ", " + apa_p(r["p_gg"]) + ")";
  return text;
}

// The page head, title line and any warnings.
void report_head(std::ostringstream& h, const BlockResults& b) {
  const json& r = b.json;
  h << "<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>countershade analysis"
    << (b.method.empty() ? "" : " — " + xml_escape(b.method)) << "</title><style>"
    << "body{font-family:sans-serif;max-width:1000px;margin:2em "
       "auto;color:#222}table{border-collapse:collapse;"
       "margin:0.5em 0 1.5em}td,th{border:1px solid #ccc;padding:2px "
       "8px;font-size:13px;text-align:right}"
       "th{background:#f3f3f3}li{margin:0.3em 0}.warn{color:#a40}</style></head><body>\n"
    << "<h1>Adjustment study analysis" << (b.method.empty() ? "" : ": " + xml_escape(b.method))
    << "</h1>\n"
    << "<p>" << r["n_subjects"]
    << " subjects analysed; JND normalisation: " << r["jnd_normalization"].get<std::string>()
    << "; λ grid step " << r["lambda_step"] << ".</p>\n";
  if (b.browser_answers > 0)
    h << "<p>" << b.browser_answers
      << " answers came from a browser (a web-exported study): their display was "
      << "not calibrated, and the CSV's device_pixel_ratio, window and user_agent columns describe "
         "it.</p>\n";
  if (!b.warnings.empty()) {
    h << "<ul>";
    for (const auto& w : b.warnings) h << "<li class=\"warn\">" << xml_escape(w) << "</li>";
    h << "</ul>\n";
  }
}

// The ANOVA statements as a list (closed by the caller).
void anova_list(std::ostringstream& h, const json& rows) {
  for (const auto& row : rows)
    h << "<li><b>" << xml_escape(row["effect"]) << "</b>: " << xml_escape(anova_statement(row))
      << "</li>";
}

// The t-tests: pairwise between questions, then λ_Best against 1 JND per scene.
void t_test_sections(std::ostringstream& h, const json& r) {
  h << "<h2>Pairwise comparisons (paired t-tests, Holm-corrected)</h2>\n<ul>";
  for (const auto& row : r["pairwise"])
    h << "<li>λ_" << xml_escape(row["a"]) << " − λ_" << xml_escape(row["b"]) << " = "
      << fixed(row["mean_diff"], 2) << " JND, t(" << df_text(row["df"])
      << ") = " << fixed(row["t"], 2) << ", " << xml_escape(apa_p(row["p_holm"])) << "</li>";
  h << "</ul>\n<h2>λ_Best against 1 JND per scene (one-sample t-tests, Holm-corrected)</h2>\n<ul>";
  for (const auto& row : r["best_vs_threshold"])
    h << "<li>" << xml_escape(row["scene"]) << ": λ_Best = " << fixed(row["mean"], 2) << " JND, t("
      << df_text(row["df"]) << ") = " << fixed(row["t"], 2) << ", "
      << xml_escape(apa_p(row["p_holm"])) << "</li>";
}

void anova_section(std::ostringstream& h, const json& rows) {
  const std::string model = rows.empty() ? "" : rows[0]["model"].get<std::string>();
  h << "<h2>Repeated-measures ANOVA: " << xml_escape(model.empty() ? "question" : model)
    << " (JND)</h2>\n";
  if (rows.empty()) {
    h << "<p>No ANOVA: too few subjects to estimate an error variance.</p>\n";
    return;
  }
  h << "<ul>";
  anova_list(h, rows);
  h << "</ul>\n"
    << html_table(rows, {"effect", "df1", "df2", "F", "p", "ges", "mauchly_W", "mauchly_p",
                         "gg_epsilon", "p_gg", "hf_epsilon", "p_hf"});
}

// λ_Best against σ: the figure and the ANOVA's σ effects, or one line where σ has one value.
void sigma_section(std::ostringstream& h, const BlockResults& b, const std::string& fig13) {
  h << "<h2>Does σ change λ_Best?</h2>\n";
  if (b.sigmas.size() < 2) {
    h << "<p>One σ value: nothing to compare across σ.</p>\n";
    return;
  }
  h << fig13 << "\n<ul>";
  for (const auto& row : b.json["anova_best_sigma"])
    if (row["effect"].get<std::string>().find("sigma") != std::string::npos)
      h << "<li><b>" << xml_escape(row["effect"])
        << "</b> on λ_Best: " << xml_escape(anova_statement(row)) << "</li>";
  h << "</ul>\n";
}

std::string report_html(const BlockResults& b, const std::string& fig12, const std::string& fig13,
                        const std::string& fits, const std::string& dendrogram) {
  const json& r = b.json;
  std::ostringstream h;
  report_head(h, b);
  h << "<h2>Chosen λ per scene</h2>\n"
    << fig12 << "\n"
    << html_table(r["descriptives"], {"scene", "question", "n", "mean", "sd", "sem"});
  anova_section(h, r["anova"]);
  sigma_section(h, b, fig13);
  t_test_sections(h, r);
  h << "</ul>\n<h2>Preference clusters (Ward)</h2>\n" << dendrogram << "\n<ul>";
  const json& c = r["clusters"];
  for (size_t k = 0; k < c["sizes"].size(); ++k)
    h << "<li>cluster " << k + 1 << ": " << c["sizes"][k] << " subjects ("
      << fixed(100.0 * c["sizes"][k].get<double>() / r["n_subjects"].get<double>(), 0)
      << " %), mean λ_Best = " << fixed(c["mean_best"][k], 2) << " JND</li>";
  h << "</ul>\n<h2>Threshold fits</h2>\n"
    << fits << "\n"
    << html_table(r["fits"], {"scene", "sigma", "question", "model", "threshold", "log_threshold",
                              "log_threshold_se", "log_sd", "n", "left_censored", "right_censored",
                              "identified", "converged", "ci_low", "ci_high"});
  if (!r["excluded_subjects"].empty())
    h << "<h2>Excluded subjects</h2>\n"
      << html_table(r["excluded_subjects"], {"subject", "reason"});
  h << "<p><small>Generated by countershade analyze.</small></p></body></html>\n";
  return h.str();
}

// Each table's columns, written as the header of a table with no rows.
const std::vector<std::pair<const char*, std::vector<std::string>>> kTableColumns = {
    {"descriptives", {"scene", "question", "n", "mean", "sd", "sem"}},
    {"descriptives_by_sigma", {"scene", "sigma", "question", "n", "mean", "sd", "sem"}},
    {"anova", {"model", "effect", "df1", "df2", "F", "p", "ges"}},
    {"anova_best_sigma", {"model", "effect", "df1", "df2", "F", "p", "ges"}},
    {"pairwise", {"a", "b", "mean_diff", "t", "df", "p", "p_holm"}},
    {"best_vs_threshold", {"scene", "mean", "t", "df", "p", "p_holm"}},
    {"fits",
     {"scene", "sigma", "question", "model", "threshold", "log_threshold", "log_threshold_se",
      "log_sd", "n", "left_censored", "right_censored", "identified", "converged"}},
    {"excluded_subjects", {"subject", "reason"}}};

}  // namespace

void write_outputs(const std::vector<BlockResults>& results, const std::filesystem::path& dir,
                   bool figures, const json& extra) {
  json all;
  if (results.size() == 1) {
    all = results[0].json;
  } else if (!results.empty()) {
    all["methods"] = json::array();
    for (const auto& b : results) all["methods"].push_back(b.json);
  }
  for (const auto& [key, value] : extra.items()) all[key] = value;
  write_text(dir / "results.json", all.dump(2) + "\n");
  for (const auto& b : results) {
    std::filesystem::path out = results.size() == 1 ? dir : dir / b.method;
    std::filesystem::create_directories(out);
    for (const auto& [table, columns] : kTableColumns)
      write_text(out / (std::string(table) + ".csv"), table_csv(b.json[table], columns));
    json clusters = json::array();
    for (size_t i = 0; i < b.subjects.size(); ++i)
      clusters.push_back({{"subject", b.subjects[i]}, {"cluster", b.cluster_labels[i]}});
    write_text(out / "clusters.csv", table_csv(clusters));
    if (!figures) continue;
    std::string fig12 = figure_questions_by_scene(b), fig13 = figure_lambda_by_sigma(b),
                fits = figure_fits(b), dendrogram = figure_dendrogram(b);
    write_text(out / "fig12_questions_by_scene.svg", fig12);
    write_text(out / "fig13_lambda_by_sigma.svg", fig13);
    write_text(out / "fits.svg", fits);
    write_text(out / "dendrogram.svg", dendrogram);
    write_text(out / "report.html", report_html(b, fig12, fig13, fits, dendrogram));
  }
}

namespace {

// A file name from text in a data file: only letters, digits, '.', '_' and '-' survive, so the
// name can never leave the output folder.
std::string figure_file_name(const std::string& scene, std::set<std::string>& taken) {
  std::string safe;
  for (unsigned char c : scene)
    safe += std::isalnum(c) || c == '.' || c == '_' || c == '-' ? char(c) : '_';
  std::string name = "psychometric-" + safe + ".svg";
  for (int i = 2; taken.count(name); ++i)
    name = "psychometric-" + safe + "-" + std::to_string(i) + ".svg";
  taken.insert(name);
  return name;
}

}  // namespace

std::vector<std::pair<std::string, std::string>> write_forced_choice_outputs(
    const ForcedChoiceResults& results, const std::filesystem::path& dir, bool figures) {
  write_text(dir / "psychometric_fits.csv", psychometric_fits_csv(results));
  std::vector<std::pair<std::string, std::string>> files;
  if (!figures) return files;
  std::set<std::string> taken;
  for (const auto& [scene, svg] : psychometric_figures(results)) {
    files.push_back({scene, figure_file_name(scene, taken)});
    write_text(dir / files.back().second, svg);
  }
  return files;
}

}  // namespace countershade::analysis
