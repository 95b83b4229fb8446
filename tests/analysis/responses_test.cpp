#include "analysis/responses.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "test_util.h"

namespace countershade::analysis {
namespace {

const char* kHeader = "subject,scene,sigma,question,lambda,lambda_step\n";

TEST(Responses, ReadsRfc4180WithBomCrlfQuotesAndUnknownColumns) {
  testing::TempDir dir;
  auto path = testing::write_file(dir / "r.csv",
                                  "\xEF\xBB\xBFsubject,note,scene,sigma,question,lambda\r\n"
                                  "S01,\"likes \"\"big\"\" halos, mostly\",dice,0.02,best,1.25\r\n"
                                  "\"S,02\",\"two\nlines\",\"feet\",0.01,low,0.3\r\n");
  auto rows = read_responses(path);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].subject, "S01");
  EXPECT_EQ(rows[0].scene, "dice");
  EXPECT_EQ(rows[0].question, Question::best);
  EXPECT_DOUBLE_EQ(rows[0].lambda, 1.25);
  EXPECT_EQ(rows[1].subject, "S,02");
  EXPECT_EQ(rows[1].scene, "feet");
  EXPECT_EQ(rows[1].source, path.string() + ":3");
}

TEST(Responses, BadInputNamesFileLineAndColumn) {
  testing::TempDir dir;
  struct Case {
    std::string text, expected;
  } cases[] = {
      {"subject,scene,sigma,question\nS1,a,0.1,low\n", "line 1: missing column 'lambda'"},
      {std::string(kHeader) + "S1,a,0.1,low,abc,0.05\n",
       "line 2, column 5 (lambda): 'abc' is not a number"},
      {std::string(kHeader) + "S1,a,0.1,medium,0.5,0.05\n",
       "line 2, column 4 (question): unknown question 'medium'"},
      {"", "file is empty"},
      {"subject,scene,sigma,question,lambda,lambda\nS1,a,0.1,low,0.5,0.5\n",
       "line 1, column 6: duplicate column 'lambda'"},
      {std::string(kHeader) + "S1,a,0.1,low,0.5\n", "line 2: expected 6 fields, found 5"},
      {std::string(kHeader) + "S1,\"a,0.1,low,0.5,0.05\n", "a quoted field is never closed"},
      {std::string(kHeader) + "S1,a,nan,low,0.5,0.05\n", "column 3 (sigma): 'nan' is not a number"},
      {std::string(kHeader) + "S1,a,0.1,low,-0.5,0.05\n",
       "column 5 (lambda): λ must not be negative"},
      // Values no stimulus grid holds: their squares overflowed the clustering (a crash) and the
      // JND scale (λ / λ_Low) turned the statistics into nulls.
      {std::string(kHeader) + "S1,a,0.1,low,1e300,0.05\n", "column 5 (lambda): λ beyond 1e6"},
      {std::string(kHeader) + "S1,a,0.1,low,1e-300,0.05\n",
       "column 5 (lambda): λ between 0 and 1e-9"},
      {std::string(kHeader) + "S1,a,0.1,low,0.5,1e300\n",
       "column 6 (lambda_step): must be positive and at most 1e6"},
      {std::string(kHeader), "no responses after the header row"},
      // Found by the analysis fuzzer: a Latin-1 subject id reached results.json, whose writer
      // threw on it (exit 1, "failure").
      {std::string(kHeader) + "S\xe9,a,0.1,low,0.5,0.05\n", "line 2, column 1: not UTF-8 text"},
      {std::string(kHeader) + "S1,\"a\xff\",0.1,low,0.5,0.05\n",
       "line 2, column 2: not UTF-8 text"},
  };
  int i = 0;
  for (const auto& c : cases) {
    auto path = testing::write_file(dir / ("bad" + std::to_string(i++) + ".csv"), c.text);
    std::string message = testing::input_error_of([&] { read_responses(path); });
    EXPECT_EQ(message.rfind(path.string(), 0), 0u) << message;
    EXPECT_NE(message.find(c.expected), std::string::npos)
        << "expected '" << c.expected << "' in: " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos);
  }
}

TEST(Responses, CsvFieldQuotesOnlyWhenNeeded) {
  EXPECT_EQ(csv_field("plain"), "plain");
  EXPECT_EQ(csv_field("a,b"), "\"a,b\"");
  EXPECT_EQ(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(csv_field("two\nlines"), "\"two\nlines\"");
}

}  // namespace
}  // namespace countershade::analysis
