// The experiments and scenes that ship in experiments/ load and validate: a user who copies a
// command from the docs starts from files the current format accepts.

#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include "render/scene.h"
#include "render/scene_loader.h"
#include "stimuli/experiment.h"
#include "test_util.h"

namespace countershade {
namespace {

namespace fs = std::filesystem;

// Every experiment file in experiments/<design>/ (experiment.json and previews alike);
// experiments/scenes/ holds example scenes, not a design.
std::set<fs::path> shipped_experiments() {
  std::set<fs::path> out;
  for (const auto& design : fs::directory_iterator(testing::source_dir() / "experiments"))
    if (design.is_directory() && design.path().filename() != "scenes")
      for (const auto& entry : fs::directory_iterator(design.path()))
        if (entry.path().extension() == ".json") out.insert(entry.path());
  return out;
}

TEST(ShippedExperiments, EveryExperimentLoadsWithItsScenesAndMethods) {
  const std::set<fs::path> files = shipped_experiments();
  ASSERT_GE(files.size(), 8u) << "the designs of the README";
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.string());
    const Experiment e = load_experiment(file);  // loads every scene file and parses every method
    EXPECT_FALSE(e.scenes.empty());
    EXPECT_FALSE(e.methods.empty());
    EXPECT_GE(e.lambda.count(), 1);
  }
}

TEST(ShippedExperiments, EveryExampleSceneLoads) {
  int scenes = 0;
  for (const auto& entry : fs::directory_iterator(testing::source_dir() / "experiments/scenes")) {
    SCOPED_TRACE(entry.path().string());
    const Scene scene = load_scene(entry.path());
    EXPECT_FALSE(scene.objects.empty());
    ++scenes;
  }
  EXPECT_GE(scenes, 5);
}

}  // namespace
}  // namespace countershade
