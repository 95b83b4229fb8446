#include "core/json_reader.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "test_util.h"

namespace countershade {
namespace {

TEST(JsonReader, ErrorsNameFileAndKeyPath) {
  nlohmann::json j = nlohmann::json::parse(R"({"a": {"list": [{"x": "text"}]}, "typo": 1})");
  JsonObject root(j, "f.json", "");
  auto items = root.object("a").objects("list");
  EXPECT_EQ(testing::input_error_of([&] { items[0].number("x"); }),
            "f.json: a.list[0].x: expected a number, got a string");
  EXPECT_EQ(testing::input_error_of([&] { items[0].number("y"); }),
            "f.json: a.list[0].y: missing required key");
  EXPECT_EQ(testing::input_error_of([&] { root.finish(); }), "f.json: typo: unknown key");
}

TEST(JsonReader, TypedAccessorsAndRanges) {
  nlohmann::json j =
      nlohmann::json::parse(R"({"v": [1, 2, 3], "g": 0.5, "n": 4, "s": "b", "f": 2.5})");
  JsonObject o(j, "f.json", "root");
  EXPECT_EQ(o.vec3("v"), glm::dvec3(1, 2, 3));
  EXPECT_EQ(o.vec3("g"), glm::dvec3(0.5));
  EXPECT_EQ(o.integer_in("n", 0, 1, 10), 4);
  EXPECT_EQ(o.choice("s", "a", {"a", "b"}), "b");
  EXPECT_NE(testing::input_error_of([&] { o.integer("f"); }).find("expected an integer"),
            std::string::npos);
  EXPECT_NE(
      testing::input_error_of([&] { o.number_in("g", 0, 1, 2); }).find("root.g: must be in [1, 2]"),
      std::string::npos);
  EXPECT_NE(testing::input_error_of([&] {
              o.choice("s", "a", {"a", "c"});
            }).find("unknown value 'b'"),
            std::string::npos);
}

TEST(JsonReader, MalformedFilesNameTheFile) {
  testing::TempDir dir;
  auto bad = testing::write_file(dir / "bad.json", "{\"a\": [1, 2,, ]}");
  std::string message = testing::input_error_of([&] { parse_json_file(bad); });
  EXPECT_EQ(message.rfind(bad.string() + ": malformed JSON", 0), 0u) << message;
  EXPECT_NE(
      testing::input_error_of([&] { parse_json_file(dir / "none.json"); }).find("no such file"),
      std::string::npos);
  auto twice =
      testing::write_file(dir / "twice.json", "{\"a\": {\"x\": 1, \"x\": 2}, \"b\": {\"x\": 3}}");
  EXPECT_NE(
      testing::input_error_of([&] { parse_json_file(twice); }).find("the key 'x' appears twice"),
      std::string::npos);
  auto empty = testing::write_file(dir / "empty.json", "");
  EXPECT_NE(testing::input_error_of([&] { parse_json_file(empty); }).find("file is empty"),
            std::string::npos);
}

}  // namespace
}  // namespace countershade
