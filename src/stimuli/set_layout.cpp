#include "stimuli/set_layout.h"

#include <cstdio>

namespace countershade {
namespace {

std::string frame_file(int frame) {
  char name[32];
  std::snprintf(name, sizeof name, "/frame-%04d.png", frame);
  return name;
}

}  // namespace

std::vector<SetUnit> all_units(const Experiment& e) {
  std::vector<SetUnit> units;
  for (size_t s = 0; s < e.scenes.size(); ++s) {
    const auto frames = e.scenes[s].frames.value_or(std::make_pair(-1, -1));
    for (int f = frames.first; f <= frames.second; ++f) {
      units.push_back({s, -1, 0, f});
      for (size_t m = 0; m < e.methods.size(); ++m)
        if (e.methods[m].applies_to(e.scenes[s].name))
          for (size_t g = 0; g < e.methods[m].sigmas.size(); ++g)
            units.push_back({s, int(m), g, f});
    }
  }
  return units;
}

std::string reference_path(const Experiment& e, size_t scene, int frame) {
  return e.scenes[scene].name + (frame < 0 ? "/reference.png" : "/reference" + frame_file(frame));
}

std::string stimulus_path(const Experiment& e, const SetUnit& u, int lambda_index) {
  const ExperimentMethod& m = e.methods[size_t(u.method)];
  const std::string folder = e.scenes[u.scene].name + "/" + m.label + "/sigma-" +
                             format_value(m.sigmas[u.sigma]) + "/lambda-" +
                             format_value(e.lambda.value(lambda_index));
  return u.frame < 0 ? folder + ".png" : folder + frame_file(u.frame);
}

std::string unit_path(const Experiment& e, const SetUnit& u, int lambda_index) {
  return u.is_reference() ? reference_path(e, u.scene, u.frame) : stimulus_path(e, u, lambda_index);
}

std::string manifest_name(int shard, int shards) {
  return shards == 1 ? "manifest.json"
                     : "manifest.shard-" + std::to_string(shard) + "-of-" + std::to_string(shards) +
                           ".json";
}

std::string journal_name(int shard, int shards) {
  return ".journal.shard-" + std::to_string(shard) + "-of-" + std::to_string(shards) + ".jsonl";
}

}  // namespace countershade
