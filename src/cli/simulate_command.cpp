// `countershade simulate`: synthetic observers writing the responses CSV (for tests and for
// planning the sample size of a study), or a forced-choice procedure replayed on a given answer
// sequence (`--procedure` with `--responses`).

#include <cmath>
#include <cstdio>
#include <memory>

#include "analysis/simulate.h"
#include "cli/commands.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "formats/responses.h"
#include "procedures/answer_file.h"
#include "procedures/registry.h"

namespace countershade::cli {
namespace {

// Prints the summary (JSON) on stdout, so that a script can read the final estimate.
void replay(const std::string& procedure, const std::string& responses, const std::string& output) {
  const auto block = procedures::read_procedure_file(procedure);
  const auto answers = procedures::read_binary_responses(responses);
  const auto result = block.settings->replay(answers, procedure);
  write_text_atomically(output, result.csv);
  std::printf("%s\n", result.summary.dump(2).c_str());
  const size_t left = result.summary["responses_left"].get<size_t>();
  std::fprintf(
      stderr, "simulate: wrote %s (%zu trials%s)\n", output.c_str(), answers.size() - left,
      left ? (", " + std::to_string(left) + " responses left after the procedure finished").c_str()
           : "");
}

// The synthetic observers' design (the options of the adjustment simulation).
void add_design_options(CLI::App* cmd, analysis::SimulationDesign& d, long long& seed) {
  cmd->add_option("--subjects", d.subjects, "Number of observers")
      ->check(CLI::Range(3, 100000))
      ->capture_default_str();
  cmd->add_option("--repetitions", d.repetitions, "Answers per cell")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  cmd->add_option("--lambda-min", d.lambda_min, "First value of the λ grid")
      ->check(within(0.0, kLargestLambda))
      ->capture_default_str();
  cmd->add_option("--lambda-step", d.lambda_step, "λ grid step")
      ->check(within(kLambdaResolution, kLargestLambda))
      ->capture_default_str();
  cmd->add_option("--lambda-max", d.lambda_max,
                  "Top of the λ grid (answers beyond it are censored there)")
      ->check(within(kLambdaResolution, kLargestLambda))
      ->capture_default_str();
  cmd->add_option("--low", d.low, "Group λ_Low")
      ->check(within(kLambdaResolution, kLargestLambda))
      ->capture_default_str();
  cmd->add_option("--answer-sd", d.answer_sd, "Within-subject SD of ln λ")
      ->check(within(0.0, 10.0))
      ->capture_default_str();
  cmd->add_option("--high-jnd", d.high_jnd, "λ_High in JND")
      ->check(within(kLambdaResolution, kLargestLambda))
      ->capture_default_str();
  cmd->add_option("--weak-fraction", d.weak_fraction,
                  "Share of observers preferring weak enhancement")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--seed", seed, "Random seed")->capture_default_str();
  cmd->add_option("--method", d.method, "The method column (one analysis block)")
      ->capture_default_str();
}

void simulate_adjustment(const analysis::SimulationDesign& d, const std::string& output) {
  if (!(d.lambda_max >= d.lambda_min + d.lambda_step))
    throw InputError("--lambda-max: must be at least one step above --lambda-min");
  if ((d.lambda_max - d.lambda_min) / d.lambda_step >= kMostLambdaValues)
    throw InputError(
        "--lambda-step: more than 100000 grid values from --lambda-min to --lambda-max");
  const double rows =
      double(d.subjects) * double(d.repetitions) * double(d.scenes.size() * d.sigmas.size()) * 3;
  if (rows > 1e7)
    throw InputError("--subjects × --repetitions: " + std::to_string(d.subjects) + " observers × " +
                     std::to_string(d.repetitions) + " repetitions would write " +
                     std::to_string(std::llround(rows)) +
                     " responses; the limit is 10000000 (about 1 GB of CSV)");
  auto responses = analysis::simulate_responses(d);
  analysis::write_responses_csv(responses, output, d.lambda_step);
  std::fprintf(stderr, "simulate: wrote %s (%zu responses from %d observers)\n", output.c_str(),
               responses.size(), d.subjects);
}

}  // namespace

void add_simulate_command(CLI::App& app) {
  auto d = std::make_shared<analysis::SimulationDesign>();
  auto output = std::make_shared<std::string>();
  auto seed = std::make_shared<long long>(1);
  auto procedure = std::make_shared<std::string>();
  auto answers = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("simulate",
                                     "Synthetic observers with known thresholds -> responses CSV; "
                                     "or a procedure replayed on given answers.");
  CLI::Option* output_option = cmd->add_option("-o,--output", *output, "CSV to write")->required();
  auto* procedure_option = cmd->add_option(
      "--procedure", *procedure, "Replay this staircase or QUEST file (docs/forced-choice.md)");
  auto* answers_option =
      cmd->add_option("--responses", *answers,
                      "With --procedure: a CSV with a 0/1 'response' column, one row per trial");
  procedure_option->needs(answers_option);
  answers_option->needs(procedure_option);
  add_design_options(cmd, *d, *seed);
  for (CLI::Option* design : cmd->get_options())
    if (design != procedure_option && design != answers_option && design != output_option &&
        design != cmd->get_help_ptr())
      design->excludes(procedure_option);
  cmd->callback([=] {
    if (!procedure->empty()) return replay(*procedure, *answers, *output);
    d->seed = uint64_t(*seed);
    simulate_adjustment(*d, *output);
  });
  cmd->footer(
      "Examples:\n  countershade simulate -o sim.csv --subjects 30 && countershade analyze sim.csv "
      "-o sim-report\n"
      "  countershade simulate --procedure quest.json --responses answers.csv -o quest-trials.csv");
}

}  // namespace countershade::cli
