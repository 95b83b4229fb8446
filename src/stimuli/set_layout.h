#pragma once
// Where each file of a stimulus set lives (docs/stimulus-sets.md), and the units of work that
// make it: a scene's reference image, or one (scene, method, σ) with all its λ; for a sequence,
// the same for every frame.

#include <string>
#include <vector>

#include "stimuli/experiment.h"

namespace countershade {

struct SetUnit {
  size_t scene = 0;
  int method = -1;  // index into experiment.methods; -1: the scene's reference image
  size_t sigma = 0;
  int frame = -1;  // the animation's frame, for a sequence; -1: a still
  bool is_reference() const { return method < 0; }
};

// Every unit of the experiment, scene by scene and frame by frame, in a fixed order (shards deal
// them out).
std::vector<SetUnit> all_units(const Experiment& e);

// "<scene>/reference.png"; a sequence's frame: "<scene>/reference/frame-NNNN.png"
std::string reference_path(const Experiment& e, size_t scene, int frame = -1);
// "<scene>/<label>/sigma-<σ>/lambda-<λ>.png"; a sequence's frame: ".../lambda-<λ>/frame-NNNN.png"
std::string stimulus_path(const Experiment& e, const SetUnit& unit, int lambda_index);
// The file of `unit` at λ index `lambda_index` (ignored for a reference).
std::string unit_path(const Experiment& e, const SetUnit& unit, int lambda_index);

// "manifest.json", or "manifest.shard-I-of-N.json" for a shard.
std::string manifest_name(int shard, int shards);
// ".journal.shard-I-of-N.jsonl"
std::string journal_name(int shard, int shards);

}  // namespace countershade
