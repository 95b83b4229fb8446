// ParameterBag: the one parser of method parameters from experiment files and command lines.
// Every read's conversions and every message, which name the value's place in the input.

#include "core/parameters.h"

#include <gtest/gtest.h>

#include <functional>

#include "core/error.h"

namespace countershade {
namespace {

// The InputError message of `f`, or "" when it throws none.
std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

ParameterBag json_bag(const nlohmann::json& j) {
  return ParameterBag::from_json(j, "exp.json", "methods[1]");
}

TEST(ParameterBag, CommandLineWordsBecomeSnakeCaseKeysInEveryForm) {
  const ParameterBag bag =
      ParameterBag::from_arguments({"--sigma-px", "4", "--lambda=2.5", "--adapt", "--no-clamp"});
  EXPECT_EQ(bag.number("sigma_px", 0), 4.0);
  EXPECT_EQ(bag.number("lambda", 0), 2.5);
  EXPECT_TRUE(bag.boolean("adapt", false));
  EXPECT_FALSE(bag.boolean("clamp", true));
  EXPECT_EQ(bag.where("sigma_px"), "--sigma-px");
  EXPECT_EQ(message_of([] {
              ParameterBag::from_arguments({"--a", "1", "--a", "2"});
            }),
            "--a: given twice");
  EXPECT_NE(message_of([] { ParameterBag::from_arguments({"4"}); }).find("unexpected argument '4'"),
            std::string::npos);
}

TEST(ParameterBag, AbsentKeysGiveTheFallbackAndRecordIt) {
  const ParameterBag bag = json_bag({{"sigma", 0.1}});
  EXPECT_EQ(bag.number("sigma", 0.5), 0.1);
  EXPECT_EQ(bag.number("gain", 0.5), 0.5);
  EXPECT_EQ(bag.integer_in("scales", 4, 1, 8), 4);
  EXPECT_EQ(bag.choice("mode", "image", {"image", "object"}), "image");
  EXPECT_EQ(bag.vec3("tint", {1, 2, 3}), glm::dvec3(1, 2, 3));
  EXPECT_FALSE(bag.optional_number("limit"));
  const auto& f = bag.fallbacks();
  EXPECT_EQ(f.at("sigma"), 0.5);  // the fallback, not the value given
  EXPECT_EQ(f.at("gain"), 0.5);
  EXPECT_EQ(f.at("scales"), 4);
  EXPECT_EQ(f.at("mode"), "image");
  EXPECT_EQ(f.at("tint"), nlohmann::json({1.0, 2.0, 3.0}));
  EXPECT_FALSE(f.count("limit"));  // an optional read has no default
}

TEST(ParameterBag, WrongTypesAndRangesNameTheKeysPlace) {
  const ParameterBag bag =
      json_bag({{"sigma", "wide"}, {"scales", 2.5}, {"lambda", 7}, {"adapt", 1}, {"mode", "x"}});
  EXPECT_EQ(message_of([&] { bag.number("sigma", 0); }),
            "exp.json: methods[1].sigma: expected a number, got a string");
  EXPECT_EQ(message_of([&] { bag.integer_in("scales", 1, 1, 8); }),
            "exp.json: methods[1].scales: expected an integer in [1, 8], got 2.5");
  EXPECT_EQ(message_of([&] { bag.number_in("lambda", 1, 0, 5); }),
            "exp.json: methods[1].lambda: must be in [0, 5], got 7");
  EXPECT_NE(message_of([&] {
              bag.boolean("adapt", false);
            }).find("methods[1].adapt: expected true or false"),
            std::string::npos);
  EXPECT_EQ(message_of([&] {
              bag.choice("mode", "a", {"a", "b"});
            }),
            "exp.json: methods[1].mode: unknown value 'x' (expected one of: a, b)");
}

TEST(ParameterBag, CommandLineTextIsConvertedOnReadAndNonFiniteNumbersRefused) {
  const ParameterBag bag = ParameterBag::from_arguments(
      {"--lambda", "nan", "--sigma", "0.1,0.2,0.3", "--tint", "0.5", "--flag", "off", "--size",
       "5%", "--n", "3e0", "--pair", "1,2"});
  EXPECT_EQ(message_of([&] { bag.number("lambda", 0); }),
            "--lambda: expected a finite number, got 'nan'");
  EXPECT_EQ(bag.numbers("sigma", {}), (std::vector<double>{0.1, 0.2, 0.3}));
  EXPECT_EQ(bag.vec3("tint", {}), glm::dvec3(0.5));  // one value: all three channels
  EXPECT_FALSE(bag.boolean("flag", true));
  EXPECT_EQ(bag.text("size"), "5%");
  EXPECT_EQ(bag.integer_in("n", 1, 1, 10), 3);
  EXPECT_EQ(message_of([&] { bag.vec3("pair", {}); }), "--pair: expected three numbers R,G,B");
}

TEST(ParameterBag, JsonListsScalarsAndTextForms) {
  const ParameterBag bag =
      json_bag({{"sigma", {0.1, 0.2}}, {"one", 0.3}, {"tint", {1, 2}}, {"size", 12}});
  EXPECT_EQ(bag.numbers("sigma", {}), (std::vector<double>{0.1, 0.2}));
  EXPECT_EQ(bag.numbers("one", {}), (std::vector<double>{0.3}));
  EXPECT_EQ(message_of([&] { bag.vec3("tint", {}); }),
            "exp.json: methods[1].tint: expected an array of 3 numbers");
  EXPECT_EQ(bag.text("size"), "12");
  EXPECT_EQ(message_of([] { json_bag(nlohmann::json::array()); }),
            "exp.json: methods[1]: expected an object, got an array");
}

TEST(ParameterBag, FinishNamesTheFirstUnreadKeyInTheOrderGivenAndTheParametersRead) {
  const ParameterBag cli =
      ParameterBag::from_arguments({"--sigma-px", "2", "--zeta", "1", "--alpha", "1"});
  cli.number("sigma_px", 1);
  cli.number("lambda", 1);
  EXPECT_EQ(message_of([&] { cli.finish("usm2d"); }),
            "--zeta: usm2d has no parameter 'zeta' (its parameters: --lambda, --sigma-px)");
  const ParameterBag none = json_bag({{"x", 1}});
  EXPECT_EQ(message_of([&] { none.finish("none"); }),
            "exp.json: methods[1].x: none has no parameter 'x' (it takes no parameters)");
  const ParameterBag skipped =
      ParameterBag::from_json({{"method", "usm2d"}}, "exp.json", "methods[0]", {"method"});
  EXPECT_EQ(message_of([&] { skipped.finish("usm2d"); }), "");  // a key the caller reads itself
  EXPECT_EQ(skipped.to_json(), nlohmann::ordered_json::object());
}

TEST(ParameterBag, SetReplacesAValueAndRecordsWhereItCameFrom) {
  ParameterBag bag = json_bag({{"sigma", {0.1, 0.2}}});
  bag.set("sigma", 0.2, "exp.json: methods[1].sigma[1]");
  EXPECT_EQ(bag.number("sigma", 0), 0.2);
  EXPECT_EQ(bag.where("sigma"), "exp.json: methods[1].sigma[1]");
  EXPECT_EQ(kebab_case("sigma_px"), "sigma-px");
}

}  // namespace
}  // namespace countershade
