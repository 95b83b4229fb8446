// `countershade adjust` with bad input: one line naming the problem, exit status 2, and no
// window (these run without a display, so reaching the window would fail differently).

#include <gtest/gtest.h>

#include "tiny_set.h"

namespace countershade {
namespace {

namespace fs = std::filesystem;

testing::CommandResult run_without_display(const std::string& arguments) {
  std::string command =
      "env -u DISPLAY " + std::string(COUNTERSHADE_BINARY) + " " + arguments + " 2>&1";
  testing::CommandResult result;
  FILE* pipe = ::popen(command.c_str(), "r");
  char buffer[4096];
  size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) result.output.append(buffer, n);
  int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

void expect_refused(const testing::CommandResult& r, const std::string& expected) {
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_EQ(testing::count_lines(r.output), 1) << r.output;
  EXPECT_NE(r.output.find(expected), std::string::npos) << r.output;
}

TEST(AdjustCli, BadInputIsRefusedBeforeAnyWindowOpens) {
  testing::TempDir dir;
  fs::path manifest = testing::make_tiny_set(dir);
  const std::string sessions = " --sessions " + (dir / "sessions").string();
  const std::string set = manifest.string();

  expect_refused(run_without_display("adjust " + (dir / "nothing/manifest.json").string() +
                                     " --subject P1" + sessions),
                 "manifest.json: no such file");
  testing::write_file(dir / "corrupt.json", "{\"format_version\": 1, \"stimuli\": [");
  expect_refused(
      run_without_display("adjust " + (dir / "corrupt.json").string() + " --subject P1" + sessions),
      "corrupt.json");
  expect_refused(run_without_display("adjust " + set + " --subject ../P1" + sessions), "--subject");
  expect_refused(run_without_display("adjust " + set + " --subject 'P 1'" + sessions), "--subject");
  expect_refused(run_without_display("adjust " + set + " --subject P1 --observer human" + sessions),
                 "--observer");
  testing::write_file(dir / "blocker", "a file");
  expect_refused(run_without_display("adjust " + set + " --subject P1 --sessions " +
                                     (dir / "blocker/sessions").string()),
                 "cannot create the sessions folder");
  expect_refused(run_without_display("adjust " + set + " --subject P1 --resume" + sessions),
                 "no session to resume");
  testing::write_file(dir / "keys.txt", "100 enter\n50 jump\n");
  expect_refused(run_without_display("adjust " + set + " --subject P1 --script " +
                                     (dir / "keys.txt").string() + sessions),
                 "keys.txt: line 2");
  // Absurd delays would hang the session: at most an hour per delay and per held key.
  for (const char* script : {"99999999999999999999 enter\n", "0 hold up 999999999999\n"}) {
    testing::write_file(dir / "keys.txt", script);
    expect_refused(run_without_display("adjust " + set + " --subject P1 --script " +
                                       (dir / "keys.txt").string() + sessions),
                   "3600000");
  }

  // Screenshots: the folder must exist and be writable before the session files exist.
  expect_refused(run_without_display("adjust " + set + " --subject P1 --screenshot " +
                                     (dir / "no/shot.png").string() + sessions),
                 "no/shot.png");
  expect_refused(run_without_display("adjust " + set + " --subject P1 --screenshot " +
                                     (dir / "shot.jpg").string() + sessions),
                 "PNG");
  expect_refused(run_without_display("adjust " + set + " --subject P1 --screenshot " +
                                     (dir / "blocker/shot.png").string() + sessions),
                 "blocker");

  // A λ that no stimulus grid holds would be recorded as an answer the analysis refuses.
  {
    std::string text = testing::read_file(manifest);
    const size_t at = text.find("\"lambda\": 0.8");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, std::string("\"lambda\": 0.8").size(), "\"lambda\": 1e300");
    const fs::path absurd = testing::write_file(manifest.parent_path() / "absurd.json", text);
    expect_refused(run_without_display("adjust " + absurd.string() + " --subject P1" + sessions),
                   "beyond ±1e6");
  }

  // A changed image, then a missing one.
  fs::path image = dir / "set/small/usm3d/sigma-0.08/lambda-0.8.png";
  std::string bytes = testing::read_file(image);
  testing::write_file(image, bytes.substr(0, bytes.size() - 1) + "x");
  expect_refused(run_without_display("adjust " + set + " --subject P1" + sessions),
                 "lambda-0.8.png: sha256 does not match");
  fs::remove(image);
  expect_refused(run_without_display("adjust " + set + " --subject P1" + sessions),
                 "lambda-0.8.png: missing image");
  // None of these left a session file behind.
  EXPECT_FALSE(fs::exists(dir / "sessions/P1_s01.csv"));
}

TEST(AdjustCli, AnExistingSessionIsNotTouchedWithoutResume) {
  testing::TempDir dir;
  fs::path manifest = testing::make_tiny_set(dir);
  fs::create_directories(dir / "sessions");
  testing::write_file(dir / "sessions/P9_s03.csv", "precious data\n");
  expect_refused(
      run_without_display("adjust " + manifest.string() + " --subject P9 --session 3 --sessions " +
                          (dir / "sessions").string()),
      "P9_s03.csv: already exists");
  EXPECT_EQ(testing::read_file(dir / "sessions/P9_s03.csv"), "precious data\n");
}

TEST(AdjustCli, WithoutADisplayTheFailureSaysSoAndLeavesNoEmptySession) {
  testing::TempDir dir;
  fs::path manifest = testing::make_tiny_set(dir);
  auto r = run_without_display("adjust " + manifest.string() + " --subject P1 --sessions " +
                               (dir / "sessions").string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("cannot open a window"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "sessions/P1_s01.csv"));
}

}  // namespace
}  // namespace countershade
