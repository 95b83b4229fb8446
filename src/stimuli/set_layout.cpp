#include "stimuli/set_layout.h"

namespace countershade {

std::vector<SetUnit> all_units(const Experiment& e) {
  std::vector<SetUnit> units;
  for (size_t s = 0; s < e.scenes.size(); ++s) {
    units.push_back({s, -1, 0});
    for (size_t m = 0; m < e.methods.size(); ++m)
      if (e.methods[m].applies_to(e.scenes[s].name))
        for (size_t g = 0; g < e.methods[m].sigmas.size(); ++g) units.push_back({s, int(m), g});
  }
  return units;
}

std::string reference_path(const Experiment& e, size_t scene) { return e.scenes[scene].name + "/reference.png"; }

std::string stimulus_path(const Experiment& e, const SetUnit& u, int lambda_index) {
  const ExperimentMethod& m = e.methods[size_t(u.method)];
  return e.scenes[u.scene].name + "/" + m.label + "/sigma-" + format_value(m.sigmas[u.sigma]) + "/lambda-" +
         format_value(e.lambda.value(lambda_index)) + ".png";
}

std::string manifest_name(int shard, int shards) {
  return shards == 1 ? "manifest.json"
                     : "manifest.shard-" + std::to_string(shard) + "-of-" + std::to_string(shards) + ".json";
}

std::string journal_name(int shard, int shards) {
  return ".journal.shard-" + std::to_string(shard) + "-of-" + std::to_string(shards) + ".jsonl";
}

}  // namespace countershade
