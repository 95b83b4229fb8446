// `countershade simulate`: synthetic observers writing the responses CSV (for tests and for
// planning the sample size of a study).

#include <cmath>
#include <cstdio>
#include <memory>

#include "analysis/simulate.h"
#include "cli/commands.h"
#include "core/error.h"
#include "formats/responses.h"

namespace countershade::cli {

void add_simulate_command(CLI::App& app) {
  auto d = std::make_shared<analysis::SimulationDesign>();
  auto output = std::make_shared<std::string>();
  auto seed = std::make_shared<long long>(1);
  CLI::App* cmd = app.add_subcommand("simulate", "Synthetic observers with known thresholds -> responses CSV.");
  cmd->add_option("-o,--output", *output, "Responses CSV to write")->required();
  cmd->add_option("--subjects", d->subjects, "Number of observers")->check(CLI::Range(3, 100000))->capture_default_str();
  cmd->add_option("--repetitions", d->repetitions, "Answers per cell")->check(CLI::Range(1, 100))->capture_default_str();
  cmd->add_option("--lambda-min", d->lambda_min, "First value of the λ grid")->check(within(0.0, kLargestLambda))->capture_default_str();
  cmd->add_option("--lambda-step", d->lambda_step, "λ grid step")->check(within(kLambdaResolution, kLargestLambda))->capture_default_str();
  cmd->add_option("--lambda-max", d->lambda_max, "Top of the λ grid (answers beyond it are censored there)")
      ->check(within(kLambdaResolution, kLargestLambda))->capture_default_str();
  cmd->add_option("--low", d->low, "Group λ_Low")->check(within(kLambdaResolution, kLargestLambda))->capture_default_str();
  cmd->add_option("--answer-sd", d->answer_sd, "Within-subject SD of ln λ")->check(within(0.0, 10.0))->capture_default_str();
  cmd->add_option("--high-jnd", d->high_jnd, "λ_High in JND")->check(within(kLambdaResolution, kLargestLambda))->capture_default_str();
  cmd->add_option("--weak-fraction", d->weak_fraction, "Share of observers preferring weak enhancement")
      ->check(CLI::Range(0.0, 1.0))->capture_default_str();
  cmd->add_option("--seed", *seed, "Random seed")->capture_default_str();
  cmd->add_option("--method", d->method, "The method column (one analysis block)")->capture_default_str();
  cmd->callback([=] {
    d->seed = uint64_t(*seed);
    if (!(d->lambda_max >= d->lambda_min + d->lambda_step))
      throw InputError("--lambda-max: must be at least one step above --lambda-min");
    if ((d->lambda_max - d->lambda_min) / d->lambda_step >= kMostLambdaValues)
      throw InputError("--lambda-step: more than 100000 grid values from --lambda-min to --lambda-max");
    const double rows = double(d->subjects) * double(d->repetitions) * double(d->scenes.size() * d->sigmas.size()) * 3;
    if (rows > 1e7)
      throw InputError("--subjects × --repetitions: " + std::to_string(d->subjects) + " observers × " +
                       std::to_string(d->repetitions) + " repetitions would write " + std::to_string(std::llround(rows)) +
                       " responses; the limit is 10000000 (about 1 GB of CSV)");
    auto responses = analysis::simulate_responses(*d);
    analysis::write_responses_csv(responses, *output, d->lambda_step);
    std::fprintf(stderr, "simulate: wrote %s (%zu responses from %d observers)\n", output->c_str(), responses.size(),
                 d->subjects);
  });
  cmd->footer("Example:\n  countershade simulate -o sim.csv --subjects 30 && countershade analyze sim.csv -o sim-report");
}

}  // namespace countershade::cli
