#pragma once
// Job scripts that make a stimulus set on a Slurm cluster (docs/stimulus-sets.md, "On a
// cluster"): an array of N shards and a merge that runs once all of them succeeded. The scripts
// name the binary, the experiment and the set folder by absolute paths, so they run from any
// working directory, and carry the experiment's sha256: a task refuses to run if the file changed.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "stimuli/experiment.h"

namespace countershade {

// The job options (each given one becomes exactly one #SBATCH line).
struct SlurmOptions {
  int shards = 1;
  std::optional<int> cpus;  // --cpus-per-task; each shard runs with --jobs SLURM_CPUS_PER_TASK
  std::string mem, time, partition, account;
  std::vector<std::string> stimuli_flags;  // passed on to every run (e.g. --no-contact-sheets)
};

struct SlurmScripts {
  std::filesystem::path array, merge;
  std::vector<std::string> submit;  // the shell commands that submit and chain them
};

// Writes DIR/slurm/array.sbatch and DIR/slurm/merge.sbatch (and DIR/slurm/logs/), for the
// experiment file `experiment` (which `e` was loaded from) and the countershade binary `binary`.
// Throws InputError for a path a script cannot hold or an option it would not pass on as given.
SlurmScripts write_slurm_scripts(const Experiment& e, const std::filesystem::path& experiment,
                                 const std::filesystem::path& dir,
                                 const std::filesystem::path& binary, const SlurmOptions& options);

}  // namespace countershade
