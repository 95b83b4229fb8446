#pragma once
// Helpers of the stimulus-set tests: a set's manifest as JSON, without its run record, and
// generation options with a thread count, a set made in shards.

#include <filesystem>
#include <fstream>
#include <string>

#include "audit/audit.h"
#include "figures/set_figures.h"
#include "formats/manifest.h"
#include "stimuli/stimulus_set.h"

namespace countershade::testing {

inline OrderedJson manifest_json(const std::filesystem::path& dir,
                                 const std::string& name = "manifest.json") {
  std::ifstream in(dir / name);
  return OrderedJson::parse(in);
}

// The manifest without the fields that differ between runs (timings, timestamps).
inline OrderedJson without_run(OrderedJson manifest) {
  manifest.erase("run");
  return manifest;
}

// How many of the audit's checks named `check` ("mean L* drift", "clipped pixels") failed.
inline size_t failed_checks(const AuditReport& report, const std::string& check) {
  size_t failed = 0;
  for (const auto& c : report.checks) failed += c.check == check && !c.passed;
  return failed;
}

// A finished set's sheets and figures, drawn as `countershade stimuli` draws them after
// generating or merging it.
inline void draw_figures(const Experiment& e, const std::filesystem::path& dir,
                         bool contact_sheets = true) {
  write_set_figures(e, dir, read_manifest(dir / "manifest.json"), contact_sheets);
}

inline GenerateOptions with_jobs(int n) {
  GenerateOptions o;
  o.jobs = n;
  return o;
}

// Generates the set in `count` shards, one after the other, without merging them.
inline void generate_in_shards(const Experiment& e, const std::filesystem::path& dir, int count) {
  for (int i = 1; i <= count; ++i) {
    GenerateOptions o;
    o.shard = i;
    o.shards = count;
    generate_stimulus_set(e, dir, o);
  }
}

}  // namespace countershade::testing
