// What `countershade methods NAME` documents is what each method's parser reads: every documented
// default equals the fallback the parser uses, every key the parser reads with a fallback is
// documented, and no documented default belongs to a key the parser never reads. A default
// changed in the documentation alone, or in the code alone, fails here.

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/parameters.h"
#include "enhance/method.h"
#include "enhance/registry.h"
#include "test_util.h"

namespace countershade {
namespace {

// A documented default as a value: "3" → 3, "true" → true, "1,0,0" → [1, 0, 0], "surface" →
// "surface". Descriptions ("all 1", "all 1/S") are not values: none.
std::optional<nlohmann::json> documented_value(const std::string& text) {
  if (text.empty() || text.rfind("all ", 0) == 0) return std::nullopt;
  if (text == "true" || text == "false") return nlohmann::json(text == "true");
  std::vector<double> numbers;
  std::stringstream parts(text);
  for (std::string part; std::getline(parts, part, ',');) {
    char* end = nullptr;
    const double v = std::strtod(part.c_str(), &end);
    if (part.empty() || *end != '\0') return nlohmann::json(text);  // a word
    numbers.push_back(v);
  }
  return numbers.size() == 1 ? nlohmann::json(numbers[0]) : nlohmann::json(numbers);
}

bool same_value(const nlohmann::json& documented, const nlohmann::json& read) {
  if (documented.is_number() && read.is_number())
    return std::abs(documented.get<double>() - read.get<double>()) <= 1e-12;
  if (documented.is_array() && read.is_array() && documented.size() == read.size()) {
    for (size_t i = 0; i < read.size(); ++i)
      if (!same_value(documented[i], read[i])) return false;
    return true;
  }
  return documented == read;
}

// Parameters that a method reads only in one of its modes, and the settings that reach them.
const std::map<std::string, std::vector<nlohmann::json>> kModes = {
    {"depth-usm", {{{"operator", "contrast"}}, {{"operator", "color"}}}},
    {"cornsweet", {{{"mode", "surface"}}}},
};

// The fallbacks a method's parser reads, over its plain parse and those of its modes, each bag
// holding nothing else but one of its σ keys (a value each takes), or nothing: the first that
// parses. `width_keys` gets the σ keys used.
std::map<std::string, nlohmann::json> parsed_fallbacks(const EnhancementMethod& method,
                                                       std::set<std::string>& width_keys) {
  std::vector<nlohmann::json> settings = {nlohmann::json::object()};
  if (kModes.count(method.name()))
    for (const auto& mode : kModes.at(method.name())) settings.push_back(mode);
  std::vector<std::string> keys = {""};
  for (const WidthAxis& axis : method.axes().widths) keys.push_back(axis.key);
  std::map<std::string, nlohmann::json> out;
  for (const nlohmann::json& setting : settings) {
    std::string errors;
    bool parsed = false;
    for (size_t k = 0; k < keys.size() && !parsed; ++k) {
      nlohmann::json given = setting;
      if (!keys[k].empty()) given[keys[k]] = 2;
      ParameterBag bag = ParameterBag::from_json(given, "test", method.name());
      try {
        method.parse(bag);
      } catch (const InputError& e) {
        errors += std::string(" | ") + e.what();
        continue;
      }
      parsed = true;
      width_keys.insert(keys[k]);
      for (const auto& [key, fallback] : bag.fallbacks()) out[key] = fallback;
    }
    if (!parsed)
      ADD_FAILURE() << method.name() << " " << setting
                    << " parses with none of its σ keys alone:" << errors;
  }
  return out;
}

TEST(DocumentedParameters, EveryMethodDocumentsTheDefaultsItsParserReads) {
  size_t compared = 0;
  for (const std::string& name : method_names()) {
    const EnhancementMethod& method = method_named(name, "test");
    std::set<std::string> width_keys;
    const auto read = parsed_fallbacks(method, width_keys);
    std::set<std::string> documented;
    for (const ParameterDoc& doc : method.parameter_docs()) {
      documented.insert(doc.key);
      const auto value = documented_value(doc.default_value);
      if (!value) continue;
      const auto it = read.find(doc.key);
      if (it == read.end()) {
        ADD_FAILURE() << name << ": '" << doc.key << "' is documented with default "
                      << doc.default_value << " but the parser reads no such key with a default";
        continue;
      }
      EXPECT_TRUE(same_value(*value, it->second))
          << name << ": '" << doc.key << "' is documented as " << doc.default_value
          << ", the parser's default is " << it->second;
      ++compared;
    }
    for (const auto& [key, fallback] : read)
      EXPECT_TRUE(documented.count(key) || width_keys.count(key))
          << name << ": '" << key << "' (default " << fallback << ") is not documented";
  }
  EXPECT_GT(compared, 30u);
}

// docs/enhancement-methods.md shows every method's axes and parameters as `countershade methods
// --markdown NAME` prints them, between its markers (scripts/update-parameter-docs rewrites them):
// the tables come from the code's own documentation, which the test above holds to the parsers.
TEST(DocumentedParameters, TheDocsTablesAreTheMethodsMarkdown) {
  const std::string doc = testing::read_file(testing::source_dir() / "docs/enhancement-methods.md");
  for (const std::string& name : method_names()) {
    const std::string begin = "<!-- countershade methods --markdown " + name + " -->\n";
    const size_t at = doc.find(begin);
    ASSERT_NE(at, std::string::npos)
        << "docs/enhancement-methods.md has no generated table for " << name;
    const size_t start = at + begin.size(),
                 end = doc.find("<!-- end of generated table -->", start);
    ASSERT_NE(end, std::string::npos) << name;
    const auto r = testing::run_cli("methods --markdown " + name);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(doc.substr(start, end - start), r.output)
        << name << ": the docs' table differs from `countershade methods --markdown " << name
        << "`; run scripts/update-parameter-docs";
    if (!find_method(name)->parameter_docs().empty()) {
      EXPECT_NE(r.output.find("| `" + find_method(name)->parameter_docs()[0].key + "` |"),
                std::string::npos)
          << name;
    }
  }
}

// The record itself: each typed read notes its fallback, whether or not the key was given.
TEST(ParameterBag, RecordsTheFallbackOfEveryTypedRead) {
  ParameterBag bag = ParameterBag::from_json({{"given", 5.0}}, "test", "m");
  bag.number("given", 1.5);
  bag.integer_in("count", 3, 0, 10);
  bag.boolean("flag", true);
  bag.choice("mode", "surface", {"surface", "image"});
  bag.vec3("colour", {1, 0, 0});
  bag.numbers("list", {0.5, 0.25});
  const auto& f = bag.fallbacks();
  EXPECT_EQ(f.at("given"), 1.5);
  EXPECT_EQ(f.at("count"), 3);
  EXPECT_EQ(f.at("flag"), true);
  EXPECT_EQ(f.at("mode"), "surface");
  EXPECT_EQ(f.at("colour"), nlohmann::json({1.0, 0.0, 0.0}));
  EXPECT_EQ(f.at("list"), nlohmann::json({0.5, 0.25}));
  EXPECT_EQ(f.count("other"), 0u);
}

}  // namespace
}  // namespace countershade
