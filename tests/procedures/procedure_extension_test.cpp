// Adding a procedure: a test-only procedure (fixed_procedure.cpp, one file with its registration
// line) is listed, replayed and run through `stimuli` and `choose` with the frame clock and a
// simulated observer, in a build of the program that includes it; the built-in procedures are
// listed by the program itself.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "../adjust/x_display.h"
#include "formats/responses.h"
#include "procedures/registry.h"
#include "test_util.h"

namespace countershade::procedures {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

testing::CommandResult run_extended(const std::string& arguments) {
  return testing::run_program(COUNTERSHADE_FIXED_PROCEDURE_BINARY, arguments);
}

TEST(ProcedureExtension, ProceduresListsEveryProcedure) {
  const auto listed = testing::run_cli("procedures");
  ASSERT_EQ(listed.exit_code, 0) << listed.output;
  for (const auto& name : procedure_names())
    EXPECT_NE(("\n" + listed.output).find("\n" + name + ": "), std::string::npos) << name << "\n"
                                                                                  << listed.output;
  EXPECT_EQ(procedure_names(), (std::vector<std::string>{"adjustment", "constant", "staircase",
                                                         "quest", "questplus"}));
  EXPECT_EQ(listed.output.find("\nfixed: "), std::string::npos);
  const auto extended = run_extended("procedures fixed");
  ASSERT_EQ(extended.exit_code, 0) << extended.output;
  EXPECT_NE(extended.output.find("fixed: One λ"), std::string::npos) << extended.output;
  EXPECT_NE(extended.output.find("trials"), std::string::npos) << extended.output;
  const auto unknown = testing::run_cli("procedures fixed");
  EXPECT_EQ(unknown.exit_code, 2) << unknown.output;
  EXPECT_NE(unknown.output.find("adjustment, constant, staircase, quest, questplus"),
            std::string::npos)
      << unknown.output;
}

TEST(ProcedureExtension, ATestProcedureRunsThroughStimuliAndChoose) {
  testing::TempDir dir;
  testing::write_file(dir / "cube.json", testing::kLitCubeScene);
  testing::write_file(dir / "experiment.json", R"({
    "version": 1, "name": "fixed", "seed": 3,
    "lambda": {"min": 0, "max": 1, "step": 0.25},
    "scenes": [{"name": "cube", "file": "cube.json", "width": 48, "height": 36}],
    "methods": [{"method": "usm3d", "sigma_fraction": [0.03, 0.08]}],
    "forced_choice": {"procedure": {"type": "fixed", "lambda": 0.75, "trials": 4}}
  })");
  const auto made = run_extended("stimuli " + (dir / "experiment.json").string() + " -o " +
                                 (dir / "set").string() + " --no-contact-sheets");
  ASSERT_EQ(made.exit_code, 0) << made.output;
  testing::XvfbServer x;
  testing::Child app({COUNTERSHADE_FIXED_PROCEDURE_BINARY, "choose",
                      (dir / "set/manifest.json").string(), "--subject", "P01", "--sessions",
                      (dir / "s").string(), "--observer", "weibull:0.5,3,4", "--frame-clock"},
                     x.display(), (dir / "log.txt").string());
  ASSERT_EQ(app.wait(300), 0) << testing::read_file(dir / "log.txt");
  const fs::path csv = dir / "s/P01_s01.forced-choice.csv";
  const CsvTable table = parse_csv(testing::read_file(csv), csv.string());
  ASSERT_EQ(table.rows.size(), 1u + 2u * 4u);  // two conditions, four trials each
  int correct = 0;
  for (size_t r = 1; r < table.rows.size(); ++r) {
    EXPECT_EQ(table.rows[r][6], "0.75") << "lambda, row " << r;
    EXPECT_EQ(table.rows[r][7], "3") << "lambda_index, row " << r;
    EXPECT_EQ(table.rows[r][15], "fixed") << "procedure, row " << r;
    correct += table.rows[r][13] == "1";
  }
  const json sidecar = json::parse(testing::read_file(dir / "s/P01_s01.forced-choice.json"));
  int recorded_correct = 0;
  for (const auto& state : sidecar["procedures"]) {
    EXPECT_EQ(state["state"]["shown"], 4) << state;
    recorded_correct += state["state"]["correct"].get<int>();
  }
  EXPECT_EQ(recorded_correct, correct);
}

TEST(ProcedureExtension, ATestProcedureIsReplayedAndCheckedLikeAnyOther) {
  testing::TempDir dir;
  testing::write_file(dir / "p.json", R"({"type": "fixed", "lambda": 0.5, "trials": 2})");
  testing::write_file(dir / "r.csv", "response\n1\n0\n1\n");
  const auto replay =
      run_extended("simulate --procedure " + (dir / "p.json").string() + " --responses " +
                   (dir / "r.csv").string() + " -o " + (dir / "out.csv").string());
  ASSERT_EQ(replay.exit_code, 0) << replay.output;
  EXPECT_EQ(testing::read_file(dir / "out.csv"), "trial,intensity,response\n1,0.5,1\n2,0.5,0\n");
  testing::write_file(dir / "p.json", R"({"type": "fixed", "lambda": 0.5, "trails": 2})");
  const auto bad =
      run_extended("simulate --procedure " + (dir / "p.json").string() + " --responses " +
                   (dir / "r.csv").string() + " -o " + (dir / "out2.csv").string());
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("p.json: trails: fixed has no parameter 'trails'"), std::string::npos)
      << bad.output;
  EXPECT_FALSE(fs::exists(dir / "out2.csv"));
}

}  // namespace
}  // namespace countershade::procedures
