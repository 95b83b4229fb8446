// `countershade analyze`: recorded sessions -> results.json, CSV tables, SVG figures and a report.

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>

#include "analysis/analysis.h"
#include "analysis/forced_choice_analysis.h"
#include "analysis/forced_choice_report.h"
#include "analysis/method_comparison.h"
#include "analysis/procedure_estimates.h"
#include "analysis/report.h"
#include "cli/commands.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/one_line.h"

namespace countershade::cli {
namespace {

namespace fs = std::filesystem;

struct AnalyzeArgs {
  std::vector<std::string> inputs;
  std::string output;
  std::string normalization = "subject";
  std::optional<double> lambda_step;
  int clusters = 2;
  std::string model = "lognormal";
  std::string psychometric_model = "weibull";
  std::string lapse = "fixed";
  int bootstrap = 1000;
  long long seed = 1;
  bool no_figures = false;
};

analysis::ForcedChoiceOptions forced_choice_options(const AnalyzeArgs& args) {
  analysis::ForcedChoiceOptions o;
  o.model = analysis::parse_threshold_model(args.psychometric_model, "--psychometric-model",
                                            analysis::kPsychometricModels);
  o.free_lapse = args.lapse == "free";
  o.bootstrap = args.bootstrap;
  o.seed = uint64_t(args.seed);
  return o;
}

void print_warnings(const std::string& block, const std::vector<std::string>& warnings) {
  for (const auto& w : warnings)
    std::fprintf(stderr, "analyze: warning%s\n",
                 one_line((block.empty() ? "" : " (" + block + ")") + ": " + w).c_str());
}

// The procedures' own estimates (QUEST+'s posterior) beside the fits, when there are any.
void write_procedure_estimates(const std::vector<fs::path>& files,
                               const analysis::ForcedChoiceResults& fits, const std::string& output,
                               nlohmann::ordered_json& block) {
  std::vector<std::string> warnings;
  const auto estimates = analysis::procedure_estimates(files, warnings);
  print_warnings("procedure estimates", warnings);
  if (estimates.empty()) return;
  block["procedure_estimates"] = analysis::procedure_estimates_json(estimates);
  write_text_atomically(fs::path(output) / "procedure_estimates.csv",
                        analysis::procedure_estimates_csv(estimates, fits));
}

void run(const AnalyzeArgs& args) {
  analysis::AnalysisOptions options;
  options.normalization = analysis::parse_jnd_normalization(args.normalization);
  options.lambda_step = args.lambda_step;
  options.clusters = args.clusters;
  options.model = analysis::parse_threshold_model(args.model, "--model", analysis::kCensoredModels);
  options.bootstrap = args.bootstrap;
  options.seed = uint64_t(args.seed);
  std::vector<fs::path> adjustment, forced_choice;  // told apart by their header
  for (const std::string& input : args.inputs)
    (analysis::is_forced_choice_file(input) ? forced_choice : adjustment).push_back(input);
  check_output_folder(args.output);
  std::vector<analysis::BlockResults> results;
  if (!adjustment.empty())
    results = analysis::analyze(analysis::read_responses(adjustment), options);
  std::optional<analysis::ForcedChoiceResults> fc;
  if (!forced_choice.empty())
    fc = analysis::analyze_forced_choice(analysis::read_forced_choice_trials(forced_choice),
                                         forced_choice_options(args));
  std::error_code ec;  // created only now: a failed analysis leaves no empty folder behind
  fs::create_directories(args.output, ec);
  if (ec || !fs::is_directory(args.output))
    throw_input_error(args.output, "cannot create the output folder");
  for (const auto& block : results) print_warnings(block.method, block.warnings);
  nlohmann::ordered_json extra = nlohmann::ordered_json::object();
  if (fc) {
    print_warnings("forced choice", fc->warnings);
    extra["forced_choice"] = analysis::forced_choice_json(*fc);
    for (const auto& [scene, file] :
         analysis::write_forced_choice_outputs(*fc, args.output, !args.no_figures))
      extra["forced_choice"]["figures"][scene] = file;
    write_procedure_estimates(forced_choice, *fc, args.output, extra["forced_choice"]);
    if (!args.no_figures)
      write_text_atomically(fs::path(args.output) / "forced-choice.html",
                            analysis::forced_choice_report_html(extra["forced_choice"]));
  }
  if (fc && !results.empty()) {
    const auto comparison = analysis::compare_methods(results, *fc);
    extra["adjustment_vs_forced_choice"] = analysis::comparison_json(comparison);
    write_text_atomically(fs::path(args.output) / "adjustment_vs_forced_choice.csv",
                          analysis::comparison_csv(comparison));
  }
  analysis::write_outputs(results, args.output, !args.no_figures, extra);
  std::fprintf(stderr, "analyze: wrote %s/results.json (%zu method block%s%s)\n",
               args.output.c_str(), results.size(), results.size() == 1 ? "" : "s",
               fc ? ", forced-choice fits" : "");
}

}  // namespace

void add_analyze_command(CLI::App& app) {
  auto args = std::make_shared<AnalyzeArgs>();
  CLI::App* cmd = app.add_subcommand(
      "analyze", "Analyse recorded sessions: JND, ANOVA, t-tests, clusters, fits.");
  cmd->add_option("responses", args->inputs,
                  "Responses CSV files and forced-choice trial CSVs, told apart by their header "
                  "(docs/data-formats)")
      ->required();
  cmd->add_option("-o,--output", args->output, "Output folder")->required();
  cmd->add_option("--normalization", args->normalization,
                  "JND scale: subject (own λ_Low) or group (mean λ_Low)")
      ->check(CLI::IsMember({"subject", "group"}))
      ->capture_default_str();
  cmd->add_option("--lambda-step", args->lambda_step,
                  "λ grid step (default: the CSV's lambda_step column)");
  cmd->add_option("--clusters", args->clusters, "Number of Ward clusters")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  cmd->add_option("--model", args->model, "Threshold model: lognormal, weibull or logistic")
      ->check(CLI::IsMember({"lognormal", "weibull", "logistic"}))
      ->capture_default_str();
  cmd->add_option(
         "--psychometric-model", args->psychometric_model,
         "Forced-choice trials: weibull, log-logistic or lognormal in log λ (log-normal also read)")
      ->check(CLI::IsMember({"weibull", "log-logistic", "lognormal", "log-normal"}))
      ->capture_default_str();
  cmd->add_option("--lapse", args->lapse,
                  "Forced-choice trials: the lapse rate fixed at 0, or free in [0, 0.1]")
      ->check(CLI::IsMember({"fixed", "free"}))
      ->capture_default_str();
  cmd->add_option("--bootstrap", args->bootstrap,
                  "Parametric bootstrap resamples per fit (0 = none)")
      ->check(CLI::Range(0, 100000))
      ->capture_default_str();
  cmd->add_option("--seed", args->seed, "Bootstrap seed")->capture_default_str();
  cmd->add_flag("--no-figures", args->no_figures, "Skip the SVG figures and the HTML report");
  cmd->callback([args] { run(*args); });
  cmd->footer(
      "Examples:\n  countershade analyze sessions/*.csv -o reports/study --bootstrap 1000\n"
      "  countershade analyze forced-choice/*.csv -o reports/2afc --psychometric-model weibull "
      "--lapse free");
}

}  // namespace countershade::cli
