// `countershade stimuli`: an experiment file -> a complete, documented stimulus set.

#include <cstdio>
#include <filesystem>
#include <memory>

#include "audit/audit.h"
#include "cli/commands.h"
#include "core/error.h"
#include "figures/set_figures.h"
#include "stimuli/slurm_scripts.h"
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
  std::string experiment, output, shard = "1/1", experiment_sha256;
  int jobs = 0;
  bool resume = false, merge = false, no_sheets = false, no_masks = false;
  std::optional<int> slurm;
  SlurmOptions cluster;
};

// --slurm N: the job scripts instead of the set (stimuli/slurm_scripts.h).
void write_cluster_scripts(const StimuliArgs& args, const Experiment& experiment) {
  if (args.shard != "1/1" || args.merge || args.resume)
    throw InputError(
        "--slurm writes the job scripts that run the shards, resume them and merge them: give it "
        "without "
        "--shard, --merge or --resume");
  SlurmOptions o = args.cluster;
  o.shards = *args.slurm;
  if (args.no_sheets) o.stimuli_flags.push_back("--no-contact-sheets");
  if (args.no_masks) o.stimuli_flags.push_back("--no-masks");
  const SlurmScripts s = write_slurm_scripts(experiment, args.experiment, args.output,
                                             std::filesystem::read_symlink("/proc/self/exe"), o);
  std::printf("stimuli: wrote %s and %s (%d shards); submit them with\n", s.array.string().c_str(),
              s.merge.string().c_str(), o.shards);
  for (const std::string& line : s.submit) std::printf("  %s\n", line.c_str());
}

// The cluster options belong to --slurm, and a job's experiment must be the one its script names.
void check_cluster_options(const StimuliArgs& args, const Experiment& experiment) {
  const SlurmOptions& c = args.cluster;
  if (!args.slurm &&
      (c.cpus || !c.mem.empty() || !c.time.empty() || !c.partition.empty() || !c.account.empty()))
    throw InputError(
        "--cpus, --mem, --time, --partition and --account are job options: give them with --slurm "
        "N");
  if (!args.experiment_sha256.empty() && args.experiment_sha256 != experiment.sha256)
    throw InputError(args.experiment + ": changed since its job scripts were written (sha256 " +
                     experiment.sha256 + ", the scripts expect " + args.experiment_sha256 +
                     "); write them again with --slurm, or restore the file");
}

// A complete set's last two steps: its sheets and figures, drawn from the manifest, then the audit.
void finish_complete_set(const Experiment& experiment, const StimuliArgs& args) {
  const std::filesystem::path manifest = std::filesystem::path(args.output) / "manifest.json";
  write_set_figures(experiment, args.output, read_manifest(manifest), !args.no_sheets);
  print_audit_summary(manifest, args.jobs);
}

void run_stimuli(const StimuliArgs& args) {
  Experiment experiment = load_experiment(args.experiment);
  check_cluster_options(args, experiment);
  if (args.slurm) return write_cluster_scripts(args, experiment);
  if (args.merge) {
    auto path = merge_shard_manifests(experiment, args.output, args.jobs);
    std::fprintf(stderr, "stimuli: merged shards into %s\n", path.string().c_str());
    return finish_complete_set(experiment, args);
  }
  GenerateOptions options;
  options.jobs = args.jobs;
  std::tie(options.shard, options.shards) = parse_shard(args.shard);
  options.resume = args.resume;
  options.masks = !args.no_masks;
  GenerateReport r = generate_stimulus_set(experiment, args.output, options);
  std::fprintf(
      stderr,
      "stimuli: %zu images written, %zu kept from an earlier run; render %.1f s, prepare %.1f s, "
      "compose %.1f s, encode %.1f s (thread time), total %.1f s\n",
      r.images_written, r.images_skipped, r.render_seconds, r.prepare_seconds, r.compose_seconds,
      r.encode_seconds, r.total_seconds);
  if (options.shards == 1) finish_complete_set(experiment, args);
}

void add_cluster_options(CLI::App* cmd, StimuliArgs& args) {
  cmd->add_option("--slurm", args.slurm,
                  "Write Slurm job scripts for N shards (DIR/slurm/array.sbatch, merge.sbatch) and "
                  "print how to submit "
                  "them, instead of making the set")
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--cpus", args.cluster.cpus,
                  "--slurm: CPUs per shard (--cpus-per-task; each shard uses them all)")
      ->check(CLI::Range(1, 1024));
  cmd->add_option("--mem", args.cluster.mem,
                  "--slurm: memory per shard, as sbatch takes it (e.g. 8G)");
  cmd->add_option("--time", args.cluster.time,
                  "--slurm: time limit per job, as sbatch takes it (e.g. 02:00:00)");
  cmd->add_option("--partition", args.cluster.partition, "--slurm: the partition to run in");
  cmd->add_option("--account", args.cluster.account, "--slurm: the account to charge");
  cmd->add_option(
      "--experiment-sha256", args.experiment_sha256,
      "Refuse to run unless the experiment file has this sha256 (the job scripts pass it)");
}

}  // namespace

void add_stimuli_command(CLI::App& app) {
  auto args = std::make_shared<StimuliArgs>();
  CLI::App* cmd = app.add_subcommand(
      "stimuli", "Generate the stimulus set of an experiment (λ×σ grids, manifest).");
  cmd->add_option("experiment", args->experiment,
                  "Experiment file (JSON, see docs/stimulus-sets.md)")
      ->required();
  cmd->add_option("-o,--output", args->output, "Set folder")->required();
  cmd->add_option("--jobs", args->jobs, "Threads (default: all cores)")->check(CLI::Range(1, 1024));
  cmd->add_option("--shard", args->shard,
                  "Make part I of N of the set (e.g. for a Slurm job array)")
      ->capture_default_str();
  cmd->add_flag("--resume", args->resume,
                "Finish an interrupted run, keeping images whose checksums match");
  cmd->add_flag("--merge", args->merge,
                "Join the shard manifests in the folder into manifest.json");
  cmd->add_flag("--no-contact-sheets", args->no_sheets, "Skip the contact sheets");
  cmd->add_flag("--no-masks", args->no_masks,
                "Do not keep the methods' masks of sequence frames (SCENE/LABEL/sigma-S/mask/), so "
                "no mask_flicker");
  add_cluster_options(cmd, *args);
  cmd->callback([args] { run_stimuli(*args); });
  cmd->footer(
      "Examples:\n"
      "  countershade stimuli experiments/ritschel2008/experiment.json -o stimuli/ritschel2008\n"
      "  countershade stimuli EXP.json -o SET --shard 2/8      # one part of a job array\n"
      "  countershade stimuli EXP.json -o SET --merge          # after all parts finished\n"
      "  countershade stimuli EXP.json -o SET --slurm 8 --cpus 4 --time 01:00:00   # job scripts "
      "for a cluster\n"
      "  countershade stimuli EXP.json -o SET --resume         # after an interruption");
}

}  // namespace countershade::cli
