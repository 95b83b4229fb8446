// The forced-choice session files at every moment a kill can leave them: a session that has its
// sidecar resumes, with the same trials as one never stopped; a sidecar without its rows where
// rows were recorded, or rows without their sidecar, are refused and left as they are.

#include "forced_choice/choice_recorder.h"

#include <gtest/gtest.h>

#include "../adjust/tiny_set.h"
#include "forced_choice/choice_run.h"
#include "formats/responses.h"
#include "runtime/study.h"

namespace countershade::forced_choice {
namespace {

namespace fs = std::filesystem;

struct ChoiceFixture {
  testing::TempDir dir;
  runtime::Study study;
  ChoiceConfig config;
  ChoiceRecorder::Identity who{"P03", 1, 17};

  ChoiceFixture()
      : study(runtime::load_study(testing::make_tiny_set(dir, "", 96, 72, 0.1), std::nullopt)),
        config(parse_choice_config(
            nlohmann::json::parse(
                R"({"procedure": {"type": "constant", "lambdas": [0.2, 1.2], "repetitions": 2}})"),
            "t", "")) {}
  fs::path sessions() const { return dir / "sessions"; }
  ChoiceFiles files() const { return choice_files(sessions(), who.subject, who.session); }

  // A recorder on `run`, new or resumed, that answers `count` trials (always the first
  // interval) and is then dropped without an end, as a killed app leaves it.
  void answer(bool resume, int count) {
    fs::create_directories(sessions());
    ChoiceRun run(study, config, who.seed);
    ChoiceRecorder recorder(study, config, who, sessions(), resume, run);
    for (int i = 0; i < count; ++i) {
      const ChoiceTrial t = *run.current();
      recorder.record(t, 0, t.target == 0, 0.5);
      run.answer(0);
    }
    recorder.save(run);
  }
  size_t rows() const { return parse_csv(testing::read_file(files().csv), "csv").rows.size() - 1; }
};

TEST(ChoiceRecorder, ASessionKilledRightAfterItsSidecarResumes) {
  for (const bool empty_file : {false, true}) {
    ChoiceFixture f;
    f.answer(false, 0);
    if (empty_file)
      testing::write_file(f.files().csv, "");  // a power cut before the header reached the disk
    else
      fs::remove(f.files().csv);  // killed between the sidecar and the trials file
    f.answer(true, 3);
    EXPECT_EQ(f.rows(), 3u) << "empty file: " << empty_file;
    const auto sidecar = nlohmann::json::parse(testing::read_file(f.files().sidecar));
    EXPECT_EQ(sidecar["runs"][0]["end"], "interrupted");
    EXPECT_EQ(sidecar["runs"][1]["answers"], 3);

    // The rows are those of a session never stopped.
    ChoiceFixture whole;
    whole.answer(false, 3);
    const auto timeless = [](const fs::path& csv) {
      auto rows = parse_csv(testing::read_file(csv), "csv").rows;
      // time_utc, and set_sha256: each fixture makes its own set, whose manifest names its folder.
      for (auto& row : rows) row.resize(row.size() - 2);
      return rows;
    };
    EXPECT_EQ(timeless(f.files().csv), timeless(whole.files().csv));
  }
}

TEST(ChoiceRecorder, RowsWithoutTheirSidecarOrASidecarWithoutItsRowsAreRefused) {
  ChoiceFixture f;
  f.answer(false, 2);  // the sidecar records the run's two rows
  const std::string rows = testing::read_file(f.files().csv);
  const std::string sidecar = testing::read_file(f.files().sidecar);

  fs::remove(f.files().csv);
  std::string message = testing::input_error_of([&] { f.answer(true, 1); });
  EXPECT_NE(message.find("records 2 answers"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(f.files().csv));
  EXPECT_EQ(testing::read_file(f.files().sidecar), sidecar);

  testing::write_file(f.files().csv, rows);
  fs::remove(f.files().sidecar);
  message = testing::input_error_of([&] { f.answer(true, 1); });
  EXPECT_NE(message.find("cannot be checked and resumed"), std::string::npos) << message;
  message = testing::input_error_of([&] { f.answer(false, 1); });
  EXPECT_NE(message.find("exists already"), std::string::npos) << message;
  EXPECT_EQ(testing::read_file(f.files().csv), rows);
  EXPECT_FALSE(fs::exists(f.files().sidecar));
}

// A sidecar edited by hand into something else is one line naming it, and is left as it is.
TEST(ChoiceRecorder, ASidecarThatIsNotOneIsRefusedInOneLine) {
  ChoiceFixture f;
  f.answer(false, 1);
  auto runs_not_objects = nlohmann::ordered_json::parse(testing::read_file(f.files().sidecar));
  runs_not_objects["runs"] = nlohmann::ordered_json::array({1, "two"});
  for (const std::string& text : {runs_not_objects.dump(), std::string("not JSON")}) {
    testing::write_file(f.files().sidecar, text);
    const std::string message = testing::input_error_of([&] { f.answer(true, 1); });
    EXPECT_NE(message.find(f.files().sidecar.string() + ": not"), std::string::npos) << message;
    EXPECT_EQ(testing::read_file(f.files().sidecar), text);
  }
}

}  // namespace
}  // namespace countershade::forced_choice
