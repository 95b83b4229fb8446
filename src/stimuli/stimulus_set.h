#pragma once
// Generates a stimulus set from an experiment: every scene rendered once, every (method, σ)
// prepared once, every λ composed from that. Files appear atomically; a journal of finished
// images lets an interrupted run resume (--resume) without redoing them; --shard I/N splits the
// work deterministically and --merge joins the shard manifests into the one a single run writes.

#include <filesystem>
#include <functional>
#include <string>

#include "formats/manifest.h"
#include "stimuli/experiment.h"

namespace countershade {

struct GenerateOptions {
  int jobs = 0;               // threads (0 = all cores)
  int shard = 1, shards = 1;  // this run's part, I of N
  bool resume = false;
  // Keep each sequence frame's method mask and record its mask flicker (false: neither, to save
  // the files or to measure what they cost).
  bool masks = true;
};

struct GenerateReport {
  size_t images_written = 0, images_skipped = 0;
  double render_seconds = 0, prepare_seconds = 0, compose_seconds = 0, encode_seconds = 0,
         total_seconds = 0;
  std::filesystem::path manifest;
};

GenerateReport generate_stimulus_set(const Experiment& experiment, const std::filesystem::path& dir,
                                     const GenerateOptions& options);

// Joins manifest.shard-*-of-N.json in `dir` into manifest.json and finishes the set as a run on
// one machine does: the same flicker measures and videos. `jobs`: threads (0 = all cores).
std::filesystem::path merge_shard_manifests(const Experiment& experiment,
                                            const std::filesystem::path& dir, int jobs = 0);

// Parses "I/N"; throws InputError.
std::pair<int, int> parse_shard(const std::string& text);

}  // namespace countershade
