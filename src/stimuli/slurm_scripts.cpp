#include "stimuli/slurm_scripts.h"

#include <algorithm>

#include "core/atomic_file.h"
#include "core/error.h"

namespace countershade {
namespace fs = std::filesystem;
namespace {

// A word for bash in single quotes; text that would need more (control characters) is refused.
std::string quoted(const std::string& text, const std::string& what) {
  if (std::any_of(text.begin(), text.end(), [](unsigned char c) { return c < 0x20 || c == 0x7f; }))
    throw InputError(what + ": '" + text +
                     "' holds a control character, which a job script cannot pass on");
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// An #SBATCH value is read by sbatch, not by the shell: it must be one plain word.
std::string sbatch_line(const std::string& option, const std::string& value) {
  if (value.empty() || std::any_of(value.begin(), value.end(), [](unsigned char c) {
        return c <= ' ' || c == 0x7f || c == '#';
      }))
    throw InputError("--" + option + ": '" + value + "' must be one word without spaces or '#'");
  return "#SBATCH --" + option + "=" + value + "\n";
}

// The #SBATCH lines every job of the set shares: the options given, and nothing else.
std::string shared_lines(const SlurmOptions& o) {
  std::string lines;
  if (o.cpus) lines += sbatch_line("cpus-per-task", std::to_string(*o.cpus));
  if (!o.mem.empty()) lines += sbatch_line("mem", o.mem);
  if (!o.time.empty()) lines += sbatch_line("time", o.time);
  if (!o.partition.empty()) lines += sbatch_line("partition", o.partition);
  if (!o.account.empty()) lines += sbatch_line("account", o.account);
  return lines;
}

// The countershade command of a job: the binary, the experiment, the folder, the sha256 check.
std::string command(const Experiment& e, const fs::path& experiment, const fs::path& dir,
                    const fs::path& binary, const SlurmOptions& o, const std::string& part) {
  std::string line = "exec " + quoted(binary.string(), "the countershade binary") + " stimuli " +
                     quoted(experiment.string(), "the experiment file") + " -o " +
                     quoted(dir.string(), "the set folder") + " " + part +
                     " --jobs \"${SLURM_CPUS_PER_TASK:-1}\" --experiment-sha256 " + e.sha256;
  for (const std::string& flag : o.stimuli_flags) line += " " + flag;
  return line + "\n";
}

std::string job_name(const Experiment& e) {
  std::string name = "countershade-" + e.name;
  std::replace_if(
      name.begin(), name.end(),
      [](unsigned char c) { return !std::isalnum(c) && c != '-' && c != '_'; }, '_');
  return name;
}

const char* kHeader = "#!/bin/bash\n";
const char* kStrict = "set -euo pipefail\n";

}  // namespace

SlurmScripts write_slurm_scripts(const Experiment& e, const fs::path& experiment,
                                 const fs::path& dir, const fs::path& binary,
                                 const SlurmOptions& o) {
  const fs::path exp = fs::absolute(experiment).lexically_normal(),
                 out = fs::absolute(dir).lexically_normal();
  const fs::path folder = out / "slurm", logs = folder / "logs";
  fs::create_directories(logs);
  const std::string n = std::to_string(o.shards);
  SlurmScripts s{folder / "array.sbatch", folder / "merge.sbatch", {}};
  write_text_atomically(
      s.array,
      std::string(kHeader) + sbatch_line("job-name", job_name(e)) + sbatch_line("array", "1-" + n) +
          shared_lines(o) + sbatch_line("output", (logs / "shard-%a.log").string()) +
          "# One shard of the set; resubmit one alone with sbatch --array=K. A run resumes its own "
          "work,\n"
          "# and refuses an experiment file that changed since this script was written.\n" +
          kStrict +
          command(e, exp, out, binary, o, "--shard \"${SLURM_ARRAY_TASK_ID}/" + n + "\" --resume"));
  write_text_atomically(
      s.merge,
      std::string(kHeader) + sbatch_line("job-name", job_name(e) + "-merge") + shared_lines(o) +
          sbatch_line("output", (logs / "merge.log").string()) +
          "# Joins the shards' manifests into manifest.json once every shard succeeded.\n" +
          kStrict + command(e, exp, out, binary, o, "--merge"));
  fs::permissions(s.array, fs::perms::owner_exec | fs::perms::group_exec, fs::perm_options::add);
  fs::permissions(s.merge, fs::perms::owner_exec | fs::perms::group_exec, fs::perm_options::add);
  s.submit = {
      "jid=$(sbatch --parsable " + quoted(s.array.string(), "the script") + " | cut -d';' -f1)",
      "sbatch --dependency=afterok:$jid " + quoted(s.merge.string(), "the script")};
  return s;
}

}  // namespace countershade
