// Stimulus sets with sequences: a scene's animation frames as stimuli, the manifest's frame
// records, reproducibility across thread counts and shards, resuming frame by frame, the flicker
// recorded per frame (against the `flicker` command's measure), and bad frame ranges.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "audit/audit.h"
#include "core/error.h"
#include "core/sha256.h"
#include "enhance/registry.h"
#include "enhance/view.h"
#include "enhance/view_plan.h"
#include "measures/flicker.h"
#include "render/scene_loader.h"
#include "stimuli/lossless_video.h"
#include "stimuli/set_journal.h"
#include "stimuli/set_test_util.h"
#include "stimuli/stimulus_set.h"
#include "test_util.h"

namespace countershade {
namespace {

namespace fs = std::filesystem;

// `extra`: more top-level keys, each followed by a comma.
fs::path write_orbit_experiment(const testing::TempDir& dir, const std::string& frames = "\"all\"",
                                const std::string& extra = "") {
  testing::write_file(dir / "orbit.json", testing::kOrbitingBoxScene);
  return testing::write_file(dir / "experiment.json", R"({
    "version": 1, "name": "sequence", "seed": 7,
    "lambda": {"min": 0, "max": 1, "step": 1}, )" + extra +
                                                          R"(
    "scenes": [{"name": "orbit", "file": "orbit.json", "frames": )" +
                                                          frames + R"(}],
    "methods": [{"method": "usm3d", "sigma": [0.1]}, {"method": "usm2d", "sigma_percent": [3]}]
  })");
}

TEST(SequenceSet, EveryFrameIsAStimulusWithItsChecksumAndTheFrameRate) {
  testing::TempDir dir;
  const Experiment e = load_experiment(write_orbit_experiment(dir));
  generate_stimulus_set(e, dir / "set", testing::with_jobs(2));
  testing::draw_figures(e, dir / "set");
  const OrderedJson m = testing::manifest_json(dir / "set");
  ASSERT_EQ(m["stimuli"].size(), 4u * (1 + 2 * 2));  // per frame: the reference and 2 methods × 2 λ
  std::map<int, int> per_frame;
  for (const auto& s : m["stimuli"]) {
    ASSERT_TRUE(s.contains("frame")) << s["file"];
    EXPECT_EQ(s["fps"], 4.0);
    const int frame = s["frame"];
    ++per_frame[frame];
    char name[32];
    std::snprintf(name, sizeof name, "frame-%04d.png", frame);
    EXPECT_EQ(fs::path(s["file"].get<std::string>()).filename(), name);
    EXPECT_EQ(s["sha256"], sha256_file(dir / "set" / s["file"].get<std::string>()));
    EXPECT_EQ(s.contains("flicker"), frame > 0) << s["file"];  // a pair needs an earlier frame
  }
  EXPECT_EQ(per_frame, (std::map<int, int>{{0, 5}, {1, 5}, {2, 5}, {3, 5}}));
  EXPECT_TRUE(verify_stimulus_set(dir / "set/manifest.json").empty());
  EXPECT_TRUE(fs::exists(dir / "set/flicker.csv"));
  EXPECT_TRUE(fs::exists(dir / "set/flicker-orbit-lambda-1.svg"));
  const std::string stable = testing::read_file(dir / "set/flicker-stable-orbit-lambda-1.svg");
  EXPECT_NE(stable.find("stable flicker at lambda 1"), std::string::npos);
  EXPECT_NE(stable.find("usm3d"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir / "set/contact-sheets/orbit-usm3d.png"));
  // Each frame's λ = 0 equals that frame's reference, and the audit pairs them so.
  const AuditReport audit = audit_stimulus_set(dir / "set/manifest.json");
  for (const auto& c : audit.checks)
    if (c.check == "lambda 0 equals reference") {
      EXPECT_TRUE(c.passed) << c.condition << ": " << c.detail;
    }
}

TEST(SequenceSet, ReproducibleAcrossThreadCountsAndShards) {
  testing::TempDir dir;
  const Experiment e = load_experiment(write_orbit_experiment(dir, "\"1:3\""));
  generate_stimulus_set(e, dir / "one", testing::with_jobs(1));
  generate_stimulus_set(e, dir / "two", testing::with_jobs(2));
  testing::generate_in_shards(e, dir / "sharded", 2);
  merge_shard_manifests(e, dir / "sharded");
  const OrderedJson one = testing::without_run(testing::manifest_json(dir / "one"));
  EXPECT_EQ(one["stimuli"].size(), 3u * 5);
  EXPECT_EQ(one, testing::without_run(testing::manifest_json(dir / "two")));
  // Flicker included: measured from the files once the shards are merged.
  EXPECT_EQ(one, testing::without_run(testing::manifest_json(dir / "sharded")));
  EXPECT_EQ(one["stimuli"][0]["frame"], 1);
}

// An interrupted run, made by hand: the journal lists every image but frame 2's, whose files are
// gone. Resuming renders frame 2 alone and ends with the uninterrupted set.
TEST(SequenceSet, ResumesFrameByFrame) {
  testing::TempDir dir;
  const Experiment e = load_experiment(write_orbit_experiment(dir));
  generate_stimulus_set(e, dir / "whole", testing::with_jobs(2));
  fs::copy(dir / "whole", dir / "cut", fs::copy_options::recursive);
  fs::remove(dir / "cut/manifest.json");
  const Manifest whole = read_manifest(dir / "whole/manifest.json");
  {
    SetJournal journal(dir / "cut/.journal.shard-1-of-1.jsonl", e.sha256);
    for (const ManifestEntry& s : whole.stimuli)
      if (s.frame->index == 2)
        fs::remove(dir / "cut" / s.file);
      else
        journal.append(s);
  }
  GenerateOptions resume = testing::with_jobs(2);
  resume.resume = true;
  const GenerateReport report = generate_stimulus_set(e, dir / "cut", resume);
  EXPECT_EQ(report.images_written, 5u);
  EXPECT_EQ(report.images_skipped, 15u);
  EXPECT_EQ(testing::without_run(testing::manifest_json(dir / "whole")),
            testing::without_run(testing::manifest_json(dir / "cut")));
}

// One frame's figures as the `flicker` command measures them (with --stable).
struct CommandFlicker {
  double flicker = 0, plain = 0, stable = 0;
};

// The `flicker` command's measure, in process: usm2d at λ = 1 over every frame of the scene.
std::map<int, CommandFlicker> rendered_flicker(const fs::path& scene_file) {
  const EnhancementMethod& usm2d = method_named("usm2d", "test");
  FlickerRender render;
  render.method = &usm2d;
  render.parameters = usm2d.parse(ParameterBag::from_json({{"sigma_percent", 3}}, "test", "usm2d"));
  Scene base = load_scene(scene_file);
  apply_request(base, usm2d.request(*render.parameters));
  FlickerOptions options;
  options.stable = kStableTolerance;
  std::map<int, CommandFlicker> out;
  measure_rendered_flicker(base, 0, base.animation->frame_count() - 1, render, options,
                           [&](int frame, const FlickerFrame&, const FlickerFrame&,
                               const PlainChange& plain, const PairFlicker& pair) {
                             out[frame] = {pair.layer.rms, plain.rms.rms, pair.stable.rms};
                           });
  return out;
}

// The set measures flicker from its files; the `flicker` command renders and measures in memory,
// through the same pair measure. They agree frame by frame, for a method and for the plain render.
TEST(SequenceSet, FlickerMatchesTheFlickerCommand) {
  testing::TempDir dir;
  generate_stimulus_set(load_experiment(write_orbit_experiment(dir)), dir / "set",
                        testing::with_jobs(2));
  const std::map<int, CommandFlicker> command = rendered_flicker(dir / "orbit.json");
  ASSERT_EQ(command.size(), 3u);
  int compared = 0;
  const OrderedJson manifest = testing::manifest_json(dir / "set");  // alive while iterating
  for (const auto& s : manifest["stimuli"]) {
    if (!s.contains("flicker")) continue;
    const int frame = s["frame"];
    if (s["method"] == "none") {
      EXPECT_NEAR(s["flicker"].get<double>(), command.at(frame).plain, 1e-4);
    }
    EXPECT_EQ(s.contains("flicker_stable"), s["method"] != "none") << s["file"];
    if (s["method"] == "usm2d" && s["lambda"] == 1.0) {
      EXPECT_NEAR(s["flicker"].get<double>(), command.at(frame).flicker, 1e-4);
      EXPECT_NEAR(s["flicker_stable"].get<double>(), command.at(frame).stable, 1e-4);
      EXPECT_GT(s["flicker_stable_pixels"].get<size_t>(), 100u);
    }
    if (s["lambda"] == 0.0 && s["method"] != "none") {
      EXPECT_EQ(s["flicker"].get<double>(), 0.0);
    }
    compared += s["method"] == "none" || (s["method"] == "usm2d" && s["lambda"] == 1.0);
  }
  EXPECT_EQ(compared, 6);
  EXPECT_GT(command.at(1).flicker, 0.05);  // usm2d does change: the comparison can tell
}

// "video": every sequence also as a lossless video that decodes to exactly its frames, the same
// bytes at any thread count, listed and checked with the set.
TEST(SequenceSet, VideosDecodeToTheirFramesAndAreReproducible) {
  testing::TempDir dir;
  const Experiment e = load_experiment(write_orbit_experiment(dir, "\"all\"", R"("video": true,)"));
  generate_stimulus_set(e, dir / "one", testing::with_jobs(1));
  generate_stimulus_set(e, dir / "two", testing::with_jobs(2));
  const OrderedJson one = testing::without_run(testing::manifest_json(dir / "one"));
  EXPECT_EQ(one, testing::without_run(testing::manifest_json(dir / "two")));
  ASSERT_EQ(one["videos"].size(), 5u);  // the reference and 2 methods × 2 λ
  for (const auto& v : one["videos"]) {
    const std::string sequence = v["sequence"];
    EXPECT_EQ(v["file"], sequence + ".mkv");
    EXPECT_EQ(v["fps"], 4.0);
    const std::vector<Image> frames = read_video_frames(dir / "one" / v["file"].get<std::string>());
    ASSERT_EQ(frames.size(), 4u);
    for (int f = 0; f < 4; ++f) {
      const Image png =
          read_image(dir / "one" / sequence / ("frame-000" + std::to_string(f) + ".png"));
      long differing = 0;
      for (size_t i = 0; i < png.pixels.size(); ++i)
        differing +=
            std::lround(png.pixels[i] * 255) != std::lround(frames[size_t(f)].pixels[i] * 255);
      EXPECT_EQ(differing, 0) << sequence << " frame " << f;
    }
  }
  EXPECT_TRUE(verify_stimulus_set(dir / "one/manifest.json").empty());
  testing::write_file(dir / "one/orbit/reference.mkv", "changed");
  EXPECT_EQ(verify_stimulus_set(dir / "one/manifest.json").size(), 1u);
  // 16-bit frames have no 8-bit video.
  EXPECT_THROW(load_experiment(write_orbit_experiment(dir, "\"all\"",
                                                      R"("video": true, "output": {"bits": 16},)")),
               InputError);
}

TEST(SequenceSet, FramesOfAStillSceneOrOutsideTheAnimationAreRefused) {
  testing::TempDir dir;
  write_orbit_experiment(dir);
  EXPECT_THROW(load_experiment(write_orbit_experiment(dir, "\"2:9\"")), InputError);
  EXPECT_THROW(load_experiment(write_orbit_experiment(dir, "\"3:1\"")), InputError);
  testing::write_file(dir / "still.json", testing::kLitCubeScene);
  std::string text = testing::read_file(dir / "experiment.json");
  text.replace(text.find("orbit.json"), 10, "still.json");
  testing::write_file(dir / "experiment.json", text);
  try {
    load_experiment(dir / "experiment.json");
    FAIL() << "a still scene with frames was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("scenes[0].frames"), std::string::npos)
        << error.what();
    EXPECT_NE(std::string(error.what()).find("has no animation"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace countershade
