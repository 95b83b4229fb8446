// The Slurm job scripts of `stimuli --slurm`: their #SBATCH lines are exactly the options given,
// they are valid bash naming everything by absolute paths, and what they cannot pass on is
// refused; a merge with shards missing names them all and writes nothing. (A real Slurm runs
// them in tests/cluster/slurm_test.sh.)

#include "stimuli/slurm_scripts.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <sstream>

#include "core/error.h"
#include "stimuli/set_test_util.h"
#include "test_util.h"

namespace countershade {
namespace {

namespace fs = std::filesystem;

fs::path write_experiment(const testing::TempDir& dir) {
  testing::write_file(dir / "orbit.json", testing::kOrbitingBoxScene);
  return testing::write_file(dir / "experiment.json", R"({
    "version": 1, "name": "cluster's test", "seed": 7, "lambda": {"min": 0, "max": 1, "step": 1},
    "scenes": [{"name": "orbit", "file": "orbit.json", "frames": "all"}],
    "methods": [{"method": "usm2d", "sigma_percent": [3]}]})");
}

std::vector<std::string> sbatch_lines(const fs::path& script) {
  std::istringstream in(testing::read_file(script));
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);)
    if (line.rfind("#SBATCH", 0) == 0) lines.push_back(line);
  return lines;
}

TEST(SlurmScripts, TheSbatchLinesAreExactlyTheOptionsGiven) {
  testing::TempDir dir;
  const fs::path file = write_experiment(dir);
  const Experiment e = load_experiment(file);
  SlurmOptions o;
  o.shards = 5;
  o.cpus = 3;
  o.time = "00:30:00";
  o.account = "vision";
  const SlurmScripts s = write_slurm_scripts(e, file, dir / "set", "/opt/bin/countershade", o);
  const std::string logs = (dir / "set" / "slurm" / "logs").string();
  EXPECT_EQ(sbatch_lines(s.array),
            (std::vector<std::string>{"#SBATCH --job-name=countershade-cluster_s_test",
                                      "#SBATCH --array=1-5", "#SBATCH --cpus-per-task=3",
                                      "#SBATCH --time=00:30:00", "#SBATCH --account=vision",
                                      "#SBATCH --output=" + logs + "/shard-%a.log"}));
  EXPECT_EQ(sbatch_lines(s.merge),
            (std::vector<std::string>{"#SBATCH --job-name=countershade-cluster_s_test-merge",
                                      "#SBATCH --cpus-per-task=3", "#SBATCH --time=00:30:00",
                                      "#SBATCH --account=vision",
                                      "#SBATCH --output=" + logs + "/merge.log"}));
  const std::string array = testing::read_file(s.array);
  EXPECT_NE(array.find("exec '/opt/bin/countershade' stimuli '" +
                       fs::absolute(file).lexically_normal().string() + "'"),
            std::string::npos);
  EXPECT_NE(array.find("--shard \"${SLURM_ARRAY_TASK_ID}/5\" --resume"), std::string::npos);
  EXPECT_NE(array.find("--experiment-sha256 " + e.sha256), std::string::npos);
  EXPECT_NE(testing::read_file(s.merge).find(" --merge "), std::string::npos);
  EXPECT_TRUE(fs::is_directory(dir / "set" / "slurm" / "logs"));
  for (const fs::path& script : {s.array, s.merge})
    EXPECT_EQ(std::system(("bash -n '" + script.string() + "'").c_str()), 0) << script;
  ASSERT_EQ(s.submit.size(), 2u);
  EXPECT_NE(s.submit[1].find("--dependency=afterok:$jid"), std::string::npos);
}

TEST(SlurmScripts, WhatAScriptCannotPassOnIsRefused) {
  testing::TempDir dir;
  const fs::path file = write_experiment(dir);
  const Experiment e = load_experiment(file);
  SlurmOptions spaces;
  spaces.partition = "two words";
  EXPECT_THROW(write_slurm_scripts(e, file, dir / "a", "/bin/countershade", spaces), InputError);
  SlurmOptions hash;
  hash.time = "1:00#x";
  EXPECT_THROW(write_slurm_scripts(e, file, dir / "b", "/bin/countershade", hash), InputError);
  EXPECT_THROW(write_slurm_scripts(e, file, dir / "c\nd", "/bin/countershade", {}), InputError);
  // A quote in a path is passed on intact.
  const SlurmScripts s = write_slurm_scripts(e, file, dir / "it's", "/bin/countershade", {});
  EXPECT_NE(testing::read_file(s.array).find("'" + (dir / "it'\\''s").string() + "'"),
            std::string::npos);
  EXPECT_EQ(std::system(("bash -n \"" + s.array.string() + "\"").c_str()), 0);
}

TEST(SlurmScripts, AMergeWithShardsMissingNamesThemAllAndWritesNothing) {
  testing::TempDir dir;
  const Experiment e = load_experiment(write_experiment(dir));
  for (int shard : {2, 4}) {
    GenerateOptions o;
    o.shard = shard;
    o.shards = 5;
    generate_stimulus_set(e, dir / "set", o);
  }
  try {
    merge_shard_manifests(e, dir / "set");
    FAIL() << "merged with shards missing";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("shards 1,3,5 of 5 have not finished"),
              std::string::npos)
        << error.what();
    EXPECT_NE(std::string(error.what()).find("sbatch --array=1,3,5"), std::string::npos)
        << error.what();
  }
  EXPECT_FALSE(fs::exists(dir / "set" / "manifest.json"));
  EXPECT_FALSE(fs::exists(dir / "set" / "flicker.csv"));
}

// Shards resubmitted on a cluster run beside the others in one folder: a resumed shard clears the
// interrupted writes of its own files only.
TEST(SlurmScripts, AResumedShardLeavesTheOtherShardsWritesAlone) {
  testing::TempDir dir;
  const Experiment e = load_experiment(write_experiment(dir));
  GenerateOptions o;
  o.shard = 1;
  o.shards = 2;
  generate_stimulus_set(e, dir / "set", o);
  // Units are dealt out round-robin: the reference frames go to shard 1, usm2d's to shard 2.
  const fs::path own = dir / "set/orbit/reference/.frame-0001.tmp-99999-0.png";
  const fs::path other = dir / "set/orbit/usm2d/sigma-3/lambda-1/.frame-0001.tmp-99999-0.png";
  fs::create_directories(other.parent_path());
  testing::write_file(own, "cut short");
  testing::write_file(other, "being written by shard 2");
  o.resume = true;
  generate_stimulus_set(e, dir / "set", o);
  EXPECT_FALSE(fs::exists(own));
  EXPECT_TRUE(fs::exists(other));
}

}  // namespace
}  // namespace countershade
