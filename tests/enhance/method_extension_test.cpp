// Adding a method: a test-only method (identity_method.cpp, one file plus one registration line)
// runs through render, stimuli and adjust in a build of the program that includes it; and no
// method name is spelled out anywhere else in the sources.

#include <gtest/gtest.h>

#include <fstream>
#include <regex>

#include "../adjust/x_display.h"
#include "analysis/responses.h"
#include "enhance/registry.h"
#include "formats/manifest.h"
#include "test_util.h"

namespace countershade {
namespace {

namespace fs = std::filesystem;

testing::CommandResult run_identity(const std::string& arguments) {
  return testing::run_program(COUNTERSHADE_IDENTITY_BINARY, arguments);
}

fs::path write_identity_experiment(const testing::TempDir& dir) {
  testing::write_file(dir / "cube.json", testing::kLitCubeScene);
  return testing::write_file(dir / "experiment.json", R"({
    "version": 1, "name": "identity", "seed": 3,
    "lambda": {"min": 0, "max": 1, "step": 0.5},
    "scenes": [{"name": "cube", "file": "cube.json", "width": 48, "height": 36}],
    "methods": [{"method": "identity", "width": [1, 2]}],
    "adjust": {"start": "zero", "side": "left"}
  })");
}

TEST(MethodExtension, ATestMethodRendersLikeAnyOther) {
  testing::TempDir dir;
  const std::string scene = testing::write_file(dir / "cube.json", testing::kLitCubeScene).string();
  auto plain = run_identity("render " + scene + " -o " + (dir / "plain.png").string() +
                            " --width 48 --height 36");
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  auto same = run_identity("render " + scene + " -o " + (dir / "same.png").string() +
                           " --width 48 --height 36 --method identity --lambda 2 --width 3");
  EXPECT_EQ(same.exit_code, 2) << "--width is the command's own option, given twice: "
                               << same.output;
  same = run_identity("render " + scene + " -o " + (dir / "same.png").string() +
                      " --width 48 --height 36 --method identity --lambda 2");
  ASSERT_EQ(same.exit_code, 0) << same.output;
  EXPECT_EQ(testing::read_file(dir / "same.png"), testing::read_file(dir / "plain.png"));
  EXPECT_NE(run_identity("methods identity").output.find("a test method"), std::string::npos);
  // Its parameters are checked by its own parser, and the regular program does not know it.
  auto bad = run_identity("render " + scene + " -o " + (dir / "bad.png").string() +
                          " --method identity --sigma 1");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.output.find("--sigma: identity has no parameter 'sigma'"), std::string::npos)
      << bad.output;
  auto unknown = testing::run_cli("render " + scene + " -o " + (dir / "x.png").string() +
                                  " --method identity");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.output.find("unknown method 'identity'"), std::string::npos) << unknown.output;
}

TEST(MethodExtension, ATestMethodMakesAStimulusSetAndRunsInTheApp) {
  testing::TempDir dir;
  const fs::path experiment = write_identity_experiment(dir);
  auto made = run_identity("stimuli " + experiment.string() + " -o " + (dir / "set").string());
  ASSERT_EQ(made.exit_code, 0) << made.output;
  Manifest manifest = read_manifest(dir / "set/manifest.json");
  ASSERT_EQ(manifest.stimuli.size(), 1u + 2u * 3u);  // the reference + 2 widths × 3 λ
  const std::string reference = testing::read_file(dir / "set/cube/reference.png");
  for (const auto& e : manifest.stimuli) {
    if (e.is_reference()) continue;
    EXPECT_EQ(e.method, "identity");
    EXPECT_EQ(e.label, "identity");
    EXPECT_EQ(e.sigma_kind, "width");
    EXPECT_EQ(testing::read_file(dir / "set" / e.file), reference) << e.file;
  }
  EXPECT_TRUE(fs::exists(dir / "set/contact-sheets/cube-identity.png"));

  testing::XvfbServer x;
  testing::Child app(
      {COUNTERSHADE_IDENTITY_BINARY, "adjust", (dir / "set/manifest.json").string(), "--subject",
       "M1", "--sessions", (dir / "sessions").string(), "--observer", "simulated:4"},
      x.display(), (dir / "log.txt").string());
  ASSERT_EQ(app.wait(300), 0) << testing::read_file(dir / "log.txt");
  auto rows = analysis::read_responses(dir / "sessions/M1_s01.csv");
  ASSERT_EQ(rows.size(), 2u * 3u);  // two conditions (the widths) × three questions
  for (const auto& r : rows) EXPECT_EQ(r.method, "identity");
}

// Which file may spell out a method's name: its own file, the registry, and (for "none", the
// manifest's word for a reference image) the formats unit.
bool may_name(const fs::path& file, const std::string& method) {
  const std::string name = file.filename().string();
  std::string own = method;
  for (char& c : own)
    if (c == '-') c = '_';
  if (name == own + ".cpp" || name == "registry.cpp") return true;
  return method == "none" && file.parent_path().filename() == "formats";
}

TEST(MethodNames, NoMethodNameLiteralOutsideItsOwnFileAndTheRegistry) {
  std::vector<std::string> offences;
  int files = 0;
  for (const char* folder : {"src", "analysis"})
    for (const auto& entry : fs::recursive_directory_iterator(testing::source_dir() / folder)) {
      const std::string ext = entry.path().extension().string();
      if (!entry.is_regular_file() || (ext != ".cpp" && ext != ".h")) continue;
      ++files;
      const std::string text = testing::read_file(entry.path());
      for (const auto& method : method_names())
        if (text.find("\"" + method + "\"") != std::string::npos && !may_name(entry.path(), method))
          offences.push_back(entry.path().string() + " names \"" + method + "\"");
    }
  EXPECT_GT(files, 50);
  EXPECT_TRUE(offences.empty()) << [&] {
    std::string all;
    for (const auto& o : offences) all += o + "\n";
    return all;
  }();
}

}  // namespace
}  // namespace countershade
