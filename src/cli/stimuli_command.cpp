// `countershade stimuli`: an experiment file -> a complete, documented stimulus set.

#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli/commands.h"
#include "core/error.h"
#include "stimuli/audit.h"
#include "stimuli/stimulus_set.h"

namespace countershade::cli {
namespace {

// The one-line audit of a finished set (`countershade audit` writes the full report).
void print_audit_summary(const std::filesystem::path& manifest, int jobs) {
  AuditOptions options;
  options.threads = jobs;
  std::fprintf(stderr, "stimuli: audit: %s (countershade audit %s -o DIR for the report)\n",
               audit_stimulus_set(manifest, options).summary().c_str(), manifest.string().c_str());
}

struct StimuliArgs {
  std::string experiment, output, shard = "1/1";
  int jobs = 0;
  bool resume = false, merge = false, no_sheets = false;
};

void run_stimuli(const StimuliArgs& args) {
  Experiment experiment = load_experiment(args.experiment);
  if (args.merge) {
    auto path = merge_shard_manifests(experiment, args.output, {args.jobs, !args.no_sheets});
    std::fprintf(stderr, "stimuli: merged shards into %s\n", path.string().c_str());
    print_audit_summary(path, args.jobs);
    return;
  }
  GenerateOptions options;
  options.jobs = args.jobs;
  std::tie(options.shard, options.shards) = parse_shard(args.shard);
  options.resume = args.resume;
  options.contact_sheets = !args.no_sheets;
  GenerateReport r = generate_stimulus_set(experiment, args.output, options);
  std::fprintf(stderr,
               "stimuli: %zu images written, %zu kept from an earlier run; render %.1f s, prepare %.1f s, "
               "compose %.1f s, encode %.1f s (thread time), total %.1f s\n",
               r.images_written, r.images_skipped, r.render_seconds, r.prepare_seconds, r.compose_seconds,
               r.encode_seconds, r.total_seconds);
  if (options.shards == 1) print_audit_summary(std::filesystem::path(args.output) / "manifest.json", args.jobs);
}

}  // namespace

void add_stimuli_command(CLI::App& app) {
  auto args = std::make_shared<StimuliArgs>();
  CLI::App* cmd = app.add_subcommand("stimuli", "Generate the stimulus set of an experiment (λ×σ grids, manifest).");
  cmd->add_option("experiment", args->experiment, "Experiment file (JSON, see docs/stimulus-sets.md)")->required();
  cmd->add_option("-o,--output", args->output, "Set folder")->required();
  cmd->add_option("--jobs", args->jobs, "Threads (default: all cores)")->check(CLI::Range(1, 1024));
  cmd->add_option("--shard", args->shard, "Make part I of N of the set (e.g. for a Slurm job array)")->capture_default_str();
  cmd->add_flag("--resume", args->resume, "Finish an interrupted run, keeping images whose checksums match");
  cmd->add_flag("--merge", args->merge, "Join the shard manifests in the folder into manifest.json");
  cmd->add_flag("--no-contact-sheets", args->no_sheets, "Skip the contact sheets");
  cmd->callback([args] { run_stimuli(*args); });
  cmd->footer(
      "Examples:\n"
      "  countershade stimuli experiments/ritschel2008/experiment.json -o stimuli/ritschel2008\n"
      "  countershade stimuli EXP.json -o SET --shard 2/8      # one part of a job array\n"
      "  countershade stimuli EXP.json -o SET --merge          # after all parts finished\n"
      "  countershade stimuli EXP.json -o SET --resume         # after an interruption");
}

}  // namespace countershade::cli
