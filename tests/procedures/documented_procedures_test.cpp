// What `countershade procedures NAME` documents is what each procedure's parser reads (every
// documented default is the fallback the parser uses, and every key read with a fallback is
// documented), and docs/forced-choice.md's tables are that output.

#include <gtest/gtest.h>

#include <map>
#include <set>

#include "core/parameters.h"
#include "procedures/registry.h"
#include "test_util.h"

namespace countershade::procedures {
namespace {

// The least each built-in procedure needs to parse: its required keys.
const std::map<std::string, nlohmann::json> kRequired = {
    {"adjustment", nlohmann::json::object()},
    {"constant", {{"lambdas", {0.5}}}},
    {"staircase", {{"startVal", 1.0}}},
    {"quest", {{"tGuess", -0.5}, {"tGuessSd", 1.0}, {"pThreshold", 0.82}, {"beta", 3.5}}},
    {"questplus",
     {{"param_domain",
       {{"threshold", {-1, 0}}, {"slope", 3}, {"lower_asymptote", 0.5}, {"lapse_rate", 0}}}}},
};

// A documented default against the parser's fallback: "4" matches 4 and [4], "db" matches "db".
bool documents(const std::string& text, const nlohmann::json& fallback) {
  if (fallback.is_array() && fallback.size() == 1) return documents(text, fallback[0]);
  if (fallback.is_boolean()) return text == (fallback.get<bool>() ? "true" : "false");
  if (fallback.is_number()) return !text.empty() && std::stod(text) == fallback.get<double>();
  return fallback.is_string() && text == fallback.get<std::string>();
}

TEST(DocumentedProcedures, EveryProcedureDocumentsTheDefaultsItsParserReads) {
  ASSERT_EQ(kRequired.size(), procedure_names().size()) << "a built-in procedure without a case";
  for (const auto& name : procedure_names()) {
    const ProcedureType& procedure = procedure_named(name, "test");
    const ParameterBag bag = ParameterBag::from_json(kRequired.at(name), "test", name);
    procedure.parse(bag);
    std::map<std::string, std::string> documented;
    for (const ParameterDoc& doc : procedure.parameter_docs())
      documented[doc.key] = doc.default_value;
    for (const auto& [key, fallback] : bag.fallbacks()) {
      ASSERT_TRUE(documented.count(key)) << name << " reads " << key << " but does not document it";
      EXPECT_TRUE(documents(documented[key], fallback))
          << name << "." << key << ": documented '" << documented[key] << "', parser uses "
          << fallback;
    }
    for (const auto& [key, text] : documented) {
      if (text.empty()) continue;
      EXPECT_TRUE(bag.fallbacks().count(key))
          << name << " documents a default for " << key << " that its parser never falls back to";
    }
  }
}

// The docs show every procedure's parameters as `countershade procedures --markdown NAME` prints
// them, between its markers (scripts/update-parameter-docs rewrites them): the forced-choice
// procedures in docs/forced-choice.md, the adjustment procedure in docs/adjustment-study.md.
TEST(DocumentedProcedures, TheDocsTablesAreTheProceduresMarkdown) {
  for (const std::string& name : procedure_names()) {
    const bool adjustment = procedure_named(name, "test").study() == Study::adjustment;
    const std::string doc_name = adjustment ? "docs/adjustment-study.md" : "docs/forced-choice.md";
    const std::string doc = testing::read_file(testing::source_dir() / doc_name);
    const std::string begin = "<!-- countershade procedures --markdown " + name + " -->\n";
    const size_t at = doc.find(begin);
    ASSERT_NE(at, std::string::npos) << doc_name << " has no generated table for " << name;
    const size_t start = at + begin.size(),
                 end = doc.find("<!-- end of generated table -->", start);
    ASSERT_NE(end, std::string::npos) << name;
    const auto r = testing::run_cli("procedures --markdown " + name);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(doc.substr(start, end - start), r.output)
        << name << ": the docs' table differs from `countershade procedures --markdown " << name
        << "`; run scripts/update-parameter-docs";
    EXPECT_NE(r.output.find("| `" + procedure_named(name, "test").parameter_docs()[0].key + "` |"),
              std::string::npos)
        << name;
  }
}

}  // namespace
}  // namespace countershade::procedures
