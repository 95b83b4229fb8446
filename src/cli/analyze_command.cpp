// `countershade analyze`: recorded sessions -> results.json, CSV tables, SVG figures and a report.

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "analysis/analysis.h"
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
  int bootstrap = 1000;
  long long seed = 1;
  bool no_figures = false;
};

void run(const AnalyzeArgs& args) {
  analysis::AnalysisOptions options;
  options.normalization = analysis::parse_jnd_normalization(args.normalization);
  options.lambda_step = args.lambda_step;
  options.clusters = args.clusters;
  options.model = analysis::parse_fit_model(args.model);
  options.bootstrap = args.bootstrap;
  options.seed = uint64_t(args.seed);
  std::vector<fs::path> inputs(args.inputs.begin(), args.inputs.end());
  check_output_folder(args.output);
  auto responses = analysis::read_responses(inputs);
  auto results = analysis::analyze(responses, options);
  std::error_code ec;  // created only now: a failed analysis leaves no empty folder behind
  fs::create_directories(args.output, ec);
  if (ec || !fs::is_directory(args.output)) throw_input_error(args.output, "cannot create the output folder");
  for (const auto& block : results)
    for (const auto& w : block.warnings)
      std::fprintf(stderr, "analyze: warning%s\n",
                   one_line((block.method.empty() ? "" : " (" + block.method + ")") + ": " + w).c_str());
  analysis::write_outputs(results, args.output, !args.no_figures);
  std::fprintf(stderr, "analyze: wrote %s/results.json (%zu method block%s)\n", args.output.c_str(), results.size(),
               results.size() == 1 ? "" : "s");
}

}  // namespace

void add_analyze_command(CLI::App& app) {
  auto args = std::make_shared<AnalyzeArgs>();
  CLI::App* cmd = app.add_subcommand("analyze", "Analyse recorded sessions: JND, ANOVA, t-tests, clusters, fits.");
  cmd->add_option("responses", args->inputs, "Responses CSV files (docs/data-formats)")->required();
  cmd->add_option("-o,--output", args->output, "Output folder")->required();
  cmd->add_option("--normalization", args->normalization, "JND scale: subject (own λ_Low) or group (mean λ_Low)")
      ->check(CLI::IsMember({"subject", "group"}))
      ->capture_default_str();
  cmd->add_option("--lambda-step", args->lambda_step, "λ grid step (default: the CSV's lambda_step column)");
  cmd->add_option("--clusters", args->clusters, "Number of Ward clusters")->check(CLI::Range(1, 100))->capture_default_str();
  cmd->add_option("--model", args->model, "Threshold model: lognormal, weibull or logistic")
      ->check(CLI::IsMember({"lognormal", "weibull", "logistic"}))
      ->capture_default_str();
  cmd->add_option("--bootstrap", args->bootstrap, "Parametric bootstrap resamples per fit (0 = none)")
      ->check(CLI::Range(0, 100000))
      ->capture_default_str();
  cmd->add_option("--seed", args->seed, "Bootstrap seed")->capture_default_str();
  cmd->add_flag("--no-figures", args->no_figures, "Skip the SVG figures and the HTML report");
  cmd->callback([args] { run(*args); });
  cmd->footer("Example:\n  countershade analyze sessions/*.csv -o reports/study --bootstrap 1000");
}

}  // namespace countershade::cli
