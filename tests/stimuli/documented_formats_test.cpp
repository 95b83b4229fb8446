// The JSON examples of the format docs load with the readers countershade itself uses: the scene
// format's complete example and its animation block, the stimulus-set experiment and the
// adjustment procedure. A user starts from these; a key renamed in the code must not leave them
// broken.

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "procedures/adjustment_block.h"
#include "procedures/choice_block.h"
#include "render/scene.h"
#include "render/scene_loader.h"
#include "stimuli/experiment.h"
#include "test_util.h"

namespace countershade {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::read_file;
using testing::source_dir;
using testing::write_file;

// The ```json blocks of a document, in order.
std::vector<std::string> json_blocks(const fs::path& doc) {
  std::vector<std::string> blocks;
  for (const testing::CodeBlock& block : testing::markdown_code_blocks(doc)) {
    if (block.language != "json") continue;
    blocks.emplace_back();
    for (const std::string& line : block.lines) blocks.back() += line + "\n";
  }
  return blocks;
}

TEST(DocumentedFormats, TheSceneFormatsCompleteExampleLoads) {
  const auto blocks = json_blocks(source_dir() / "docs/scene-format.md");
  ASSERT_EQ(blocks.size(), 2u) << "the complete example and the animation block";
  // Its mesh paths start ../../data, as from experiments/scenes/.
  testing::TempDir dir;
  fs::create_symlink(source_dir() / "data", dir / "data");
  fs::create_directories(dir / "a/b");
  const Scene scene = load_scene(write_file(dir / "a/b/scene.json", blocks[0]));
  EXPECT_EQ(scene.objects.size(), 4u);
  EXPECT_EQ(scene.point_lights.size(), 1u);
  EXPECT_EQ(scene.directional_lights.size(), 1u);
  EXPECT_TRUE(scene.environment.has_value());
}

TEST(DocumentedFormats, TheAnimationBlockLoadsIntoASceneWithItsLightAndObject) {
  const auto blocks = json_blocks(source_dir() / "docs/scene-format.md");
  ASSERT_EQ(blocks.size(), 2u);
  json scene = json::parse(testing::kOrbitingBoxScene);  // light 0 directional, an object "box"
  scene["animation"] = json::parse("{" + blocks[1] + "}")["animation"];
  testing::TempDir dir;
  const Scene loaded = load_scene(write_file(dir / "scene.json", scene.dump()));
  ASSERT_TRUE(loaded.animation.has_value());
  EXPECT_EQ(loaded.animation->frame_count(), 60);  // 2 s at 30 fps
}

TEST(DocumentedFormats, TheExperimentExampleLoads) {
  const auto blocks = json_blocks(source_dir() / "docs/stimulus-sets.md");
  ASSERT_EQ(blocks.size(), 1u);
  testing::TempDir dir;
  fs::create_directories(dir / "scenes");
  fs::copy_file(source_dir() / "experiments/ritschel2008/scenes/chamfer.json",
                dir / "scenes/chamfer.json");
  const Experiment e = load_experiment(write_file(dir / "experiment.json", blocks[0]));
  EXPECT_EQ(e.methods.size(), 3u);
  EXPECT_EQ(e.lambda.count(), 61);  // 0 … 3 in steps of 0.05
}

TEST(DocumentedFormats, TheProcedureExampleParses) {
  const auto blocks = json_blocks(source_dir() / "docs/adjustment-study.md");
  ASSERT_EQ(blocks.size(), 1u);
  const procedures::StudyConfig config =
      procedures::parse_study_config(json::parse(blocks[0]), "adjustment-study.md", "");
  EXPECT_EQ(config.plan.repetitions, 2);
  EXPECT_EQ(config.plan.practice_trials, 2);
  ASSERT_EQ(config.conditions.size(), 1u);
  EXPECT_EQ(config.conditions[0].method, "usm3d");
}

TEST(DocumentedFormats, TheForcedChoiceExampleParses) {
  const auto blocks = json_blocks(source_dir() / "docs/forced-choice.md");
  ASSERT_EQ(blocks.size(), 3u);
  const auto config =
      procedures::parse_choice_config(json::parse(blocks[0]), "forced-choice.md", "");
  EXPECT_EQ(config.procedure.type, "quest");
  EXPECT_EQ(config.to_json()["trials"], 40);
  EXPECT_EQ(config.practice_trials, 2);
  const auto mixed =
      procedures::parse_choice_config(json::parse(blocks[1]), "forced-choice.md", "");
  EXPECT_EQ(mixed.procedure.type, "constant");
  EXPECT_EQ(mixed.procedure_of("bunny", "usm3d", 0.03).type, "staircase");
  EXPECT_EQ(mixed.procedure_of("bunny", "usm3d", 0.08).type, "questplus");
  EXPECT_EQ(mixed.procedure_of("bunny", "usm3d", 0.05).type, "constant");
  const auto questplus =
      procedures::parse_choice_config(json::parse(blocks[2]), "forced-choice.md", "");
  EXPECT_EQ(questplus.procedure.type, "questplus");
  EXPECT_EQ(questplus.to_json()["trials"], 80);
}

}  // namespace
}  // namespace countershade
