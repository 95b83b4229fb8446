// Stimulus sets: reproducibility across runs and thread counts, shards, manifest integrity, grid
// consistency, resume after a kill, and bad experiment files.

#include "stimuli/stimulus_set.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <set>
#include <thread>

#include "core/error.h"
#include "enhance/lightness.h"
#include "stimuli/set_test_util.h"
#include "test_util.h"

namespace countershade {
namespace {

namespace fs = std::filesystem;

// A small experiment: the Cornsweet cube, sampled adaptively to a noise budget, and a grey control
// with a fixed count; three methods.
fs::path write_cube_and_grey_experiment(const testing::TempDir& dir, int width = 96,
                                        int height = 72, double step = 0.5) {
  std::string cube = testing::kLitCubeScene;
  const std::string fixed = R"("render": {"spp": 2})";
  cube.replace(cube.find(fixed), fixed.size(),
               R"("render": {"noise": {"target": 0.8, "max_spp": 64}})");
  testing::write_file(dir / "cube.json", cube);
  testing::write_file(dir / "grey.json", R"({
    "version": 1,
    "camera": {"eye": [0, 5, 0], "target": [0, 0, 0], "up": [0, 0, -1], "projection": "orthographic", "height_world": 2,
               "width": 64, "height": 48},
    "render": {"spp": 2},
    "objects": [{"shape": {"type": "plane", "size": 4, "subdivisions": 16}, "material": {"albedo": 0.4}}],
    "lights": [{"type": "directional", "direction": [0, 1, 0], "irradiance": 1.2}]
  })");
  return testing::write_file(dir / "experiment.json", R"({
    "version": 1, "name": "test", "seed": 5,
    "lambda": {"min": 0, "max": 2, "step": )" + format_value(step) +
                                                          R"(},
    "scenes": [{"name": "cube", "file": "cube.json", "width": )" +
                                                          std::to_string(width) +
                                                          R"(, "height": )" +
                                                          std::to_string(height) + R"(},
               {"name": "grey", "file": "grey.json"}],
    "methods": [{"method": "usm3d", "sigma_fraction": [0.03, 0.08]},
                {"method": "depth-usm", "operator": "darken", "kernel_percent": [4]},
                {"method": "usm2d", "sigma_percent": [1]}],
    "contact_sheet": {"columns": 3}
  })");
}

TEST(StimulusSet, ReproducibleAcrossRunsAndThreadCounts) {
  testing::TempDir dir;
  Experiment e = load_experiment(write_cube_and_grey_experiment(dir));
  generate_stimulus_set(e, dir / "a", testing::with_jobs(1));
  generate_stimulus_set(e, dir / "b", testing::with_jobs(2));
  testing::draw_figures(e, dir / "a");
  OrderedJson a = testing::manifest_json(dir / "a"), b = testing::manifest_json(dir / "b");
  EXPECT_EQ(testing::without_run(a), testing::without_run(b));
  EXPECT_EQ(a["stimuli"].size(), 2u * (1 + 4 * 5));  // per scene: reference + 4 (method, σ) × 5 λ
  for (const auto& s : a["stimuli"])
    EXPECT_EQ(testing::read_file(dir / "a" / s["file"].get<std::string>()),
              testing::read_file(dir / "b" / s["file"].get<std::string>()));
  EXPECT_TRUE(a.contains("run"));
  EXPECT_TRUE(fs::exists(dir / "a/contact-sheets/cube-usm3d.png"));
}

// Every file under `dir`, as paths relative to it.
std::set<std::string> files_under(const fs::path& dir) {
  std::set<std::string> out;
  for (const auto& f : fs::recursive_directory_iterator(dir))
    if (f.is_regular_file()) out.insert(fs::relative(f.path(), dir).string());
  return out;
}

TEST(StimulusSet, ShardsMergeIntoTheSingleRunManifest) {
  testing::TempDir dir;
  Experiment e = load_experiment(write_cube_and_grey_experiment(dir));
  generate_stimulus_set(e, dir / "single", testing::with_jobs(2));
  testing::generate_in_shards(e, dir / "sharded", 3);
  EXPECT_FALSE(fs::exists(dir / "sharded/manifest.json"));
  merge_shard_manifests(e, dir / "sharded");
  testing::draw_figures(e, dir / "single");
  testing::draw_figures(e, dir / "sharded");
  EXPECT_EQ(testing::without_run(testing::manifest_json(dir / "single")),
            testing::without_run(testing::manifest_json(dir / "sharded")));
  EXPECT_TRUE(verify_stimulus_set(dir / "sharded/manifest.json").empty());
  // The same files (sheets and figures included), apart from the parts' manifests.
  std::set<std::string> merged = files_under(dir / "sharded");
  std::erase_if(merged, [](const std::string& f) { return f.rfind("manifest.shard-", 0) == 0; });
  EXPECT_EQ(files_under(dir / "single"), merged);
  EXPECT_TRUE(merged.count("contact-sheets/cube-usm3d.png"));
  // Without sheets, the figures of a merged set have none.
  testing::generate_in_shards(e, dir / "bare", 2);
  merge_shard_manifests(e, dir / "bare", 2);
  testing::draw_figures(e, dir / "bare", false);
  EXPECT_FALSE(fs::exists(dir / "bare/contact-sheets"));
}

TEST(StimulusSet, ManifestListsExactlyTheFilesWithTheirChecksums) {
  testing::TempDir dir;
  Experiment e = load_experiment(write_cube_and_grey_experiment(dir));
  generate_stimulus_set(e, dir / "set", testing::with_jobs(2));
  EXPECT_TRUE(verify_stimulus_set(dir / "set/manifest.json").empty());
  const OrderedJson manifest =
      testing::manifest_json(dir / "set");  // keep it alive while iterating
  for (const auto& s : manifest["stimuli"]) {
    std::string file = s["file"].get<std::string>();
    EXPECT_EQ(file.find(".."), std::string::npos);
    EXPECT_FALSE(fs::path(file).is_absolute());
    EXPECT_EQ(s["size"].get<uintmax_t>(), fs::file_size(dir / "set" / file));
  }
  // A changed file and an unlisted file are both reported.
  auto some = manifest["stimuli"][3]["file"].get<std::string>();
  std::ofstream(dir / "set" / some, std::ios::app) << "x";
  fs::copy_file(dir / "set/cube/reference.png", dir / "set/cube/stray.png");
  auto problems = verify_stimulus_set(dir / "set/manifest.json");
  ASSERT_EQ(problems.size(), 3u);  // size and sha256 of the changed file, the stray file
  EXPECT_THROW(resolve_in_set(dir.path(), "../outside.png"), InputError);
  EXPECT_THROW(resolve_in_set(dir.path(), "/etc/passwd"), InputError);
}

TEST(StimulusSet, LambdaZeroEqualsTheReferenceAndUsm3dGrowsWithLambda) {
  testing::TempDir dir;
  Experiment e = load_experiment(write_cube_and_grey_experiment(dir, 128, 96, 0.25));
  generate_stimulus_set(e, dir / "set", testing::with_jobs(2));
  OrderedJson m = testing::manifest_json(dir / "set");
  std::map<std::string, std::string> reference_sha;
  for (const auto& s : m["stimuli"])
    if (s["method"] == "none") reference_sha[s["scene"]] = s["sha256"];
  int zero = 0;
  for (const auto& s : m["stimuli"]) {
    if (s["method"] == "none" || s["lambda_index"] != 0) continue;
    EXPECT_EQ(s["sha256"], reference_sha[s["scene"]]) << s["file"];
    ++zero;
  }
  EXPECT_EQ(zero, 2 * 4);
  // The grey control is unchanged by every λ of usm3d.
  for (const auto& s : m["stimuli"])
    if (s["scene"] == "grey" && s["method"] == "usm3d") {
      EXPECT_EQ(s["sha256"], reference_sha["grey"]) << s["file"];
    }
  // Mean |ΔL*| against the reference grows with λ at every σ.
  Image reference = read_image(dir / "set/cube/reference.png");
  auto ref_lab = display_to_lab(reference, DisplayEncoding::srgb());
  for (double sigma : {0.03, 0.08}) {
    double previous = -1;
    for (int l = 0; l < e.lambda.count(); ++l) {
      std::string file = "cube/usm3d/sigma-" + format_value(sigma) + "/lambda-" +
                         format_value(e.lambda.value(l)) + ".png";
      auto lab = display_to_lab(read_image(dir / "set" / file), DisplayEncoding::srgb());
      double mean = 0;
      for (size_t i = 0; i < lab.size(); ++i)
        mean += std::abs(lab[i].L - ref_lab[i].L) / double(lab.size());
      EXPECT_GT(mean, previous) << file;
      previous = mean;
    }
  }
}

// Runs the real binary and kills it with SIGKILL once a few images are journalled.
TEST(StimulusSet, ResumeAfterAKillGivesTheUninterruptedSet) {
  testing::TempDir dir;
  fs::path experiment = write_cube_and_grey_experiment(dir, 320, 240, 0.05);
  Experiment e = load_experiment(experiment);
  generate_stimulus_set(e, dir / "whole", testing::with_jobs(2));
  pid_t child = ::fork();
  if (child == 0) {
    ::execl(COUNTERSHADE_BINARY, COUNTERSHADE_BINARY, "stimuli", experiment.c_str(), "-o",
            (dir / "cut").c_str(), "--jobs", "1", "--no-contact-sheets", (char*)nullptr);
    ::_exit(127);
  }
  fs::path journal = dir / "cut/.journal.shard-1-of-1.jsonl";
  auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline) {
    std::error_code ec;
    if (fs::exists(journal, ec) && fs::file_size(journal, ec) > 2000) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ::kill(child, SIGKILL);
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the run finished before it could be interrupted";
  EXPECT_FALSE(fs::exists(dir / "cut/manifest.json"));
  // A write cut short by the kill may have left its temporary file; make sure one is there.
  testing::write_file(dir / "cut/cube/.lambda-9.tmp-1-0.png", "partial");
  auto again = testing::run_cli("stimuli " + experiment.string() + " -o " + (dir / "cut").string());
  EXPECT_EQ(again.exit_code, 2) << "an unfinished set must not be overwritten without --resume: "
                                << again.output;
  GenerateOptions resume = testing::with_jobs(2);
  resume.resume = true;
  // Resuming with another experiment file is refused rather than mixing two designs.
  Experiment other = load_experiment(write_cube_and_grey_experiment(dir, 320, 240, 0.1));
  EXPECT_THROW(generate_stimulus_set(other, dir / "cut", resume), InputError);
  GenerateReport report = generate_stimulus_set(e, dir / "cut", resume);
  EXPECT_GT(report.images_skipped, 0u);
  EXPECT_GT(report.images_written, 0u);
  EXPECT_EQ(testing::without_run(testing::manifest_json(dir / "whole")),
            testing::without_run(testing::manifest_json(dir / "cut")));
  auto problems = verify_stimulus_set(dir / "cut/manifest.json");
  EXPECT_TRUE(problems.empty()) << problems.front();
  EXPECT_FALSE(fs::exists(dir / "cut/cube/.lambda-9.tmp-1-0.png"));
}

TEST(StimulusSet, BadExperimentFilesFailWithOneLineBeforeRendering) {
  testing::TempDir dir;
  write_cube_and_grey_experiment(dir);
  std::string base = testing::read_file(dir / "experiment.json");
  auto variant = [&](const std::string& from, const std::string& to) {
    std::string text = base;
    text.replace(text.find(from), from.size(), to);
    return text;
  };
  struct Case {
    std::string text, expected;
  } cases[] = {
      {variant("\"file\": \"cube.json\"", "\"file\": \"nope.json\""), "unknown scene"},
      {variant("\"min\": 0, \"max\": 2", "\"min\": 2, \"max\": 1"), "the λ range is empty"},
      {variant("\"step\": 0.5", "\"step\": 0"), "lambda.step: must be positive"},
      {variant("\"step\": 0.5", "\"step\": -0.1"), "lambda.step: must be positive"},
      // An absurd λ overflowed the decimal rounding to inf, and a count past INT_MAX wrapped.
      {variant("\"min\": 0, \"max\": 2", "\"min\": 0, \"max\": 1e300"), "lambda.max: beyond ±1e6"},
      {variant("\"min\": 0, \"max\": 2", "\"min\": -1e7, \"max\": 2"), "lambda.min: beyond ±1e6"},
      {variant("\"step\": 0.5", "\"step\": 1e-12"), "more than 100000 λ values"},
      {variant("{\"name\": \"grey\"", "{\"name\": \"cube\""), "duplicate scene name 'cube'"},
      {variant("\"method\": \"usm2d\"", "\"method\": \"blur\""), "unknown method 'blur'"},
      {variant("\"sigma_fraction\": [0.03, 0.08]", "\"sigma_fraction\": []"),
       "the σ list is empty"},
      {variant("\"seed\": 5", "\"seed\": 5, \"colour\": 1"), "colour: unknown key"},
      // The adjustment procedure is checked with the experiment, not first in front of a
      // participant.
      {variant("\"seed\": 5", "\"seed\": 5, \"adjust\": {\"repetitions\": -1}"),
       "adjust.repetitions"},
      {variant("\"seed\": 5", "\"seed\": 5, \"adjust\": {\"repetitons\": 2}"),
       "adjust.repetitons: the adjust block has no parameter 'repetitons'"},
      {variant("\"seed\": 5", "\"seed\": 5, \"audit\": {\"max_drift\": -1}"), "audit.max_drift"},
  };
  int i = 0;
  for (const auto& c : cases) {
    auto file = testing::write_file(dir / ("bad" + std::to_string(i++) + ".json"), c.text);
    auto r = testing::run_cli("stimuli " + file.string() + " -o " + (dir / "out").string());
    EXPECT_EQ(r.exit_code, 2) << c.expected << "\n" << r.output;
    EXPECT_EQ(testing::count_lines(r.output), 1) << r.output;
    EXPECT_NE(r.output.find(c.expected), std::string::npos) << r.output;
  }
  EXPECT_FALSE(fs::exists(dir / "out/cube")) << "nothing rendered";
  // An output folder that cannot be written.
  testing::write_file(dir / "blocker", "a file, not a folder");
  auto r = testing::run_cli("stimuli " + (dir / "experiment.json").string() + " -o " +
                            (dir / "blocker/set").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("cannot create the output folder"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace countershade
