// `countershade procedures`: the procedures an experiment may run (the adjust block, and those a
// forced_choice block's `procedure` or a `simulate --procedure` file may name), and the parameters
// each takes.

#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "procedures/registry.h"

namespace countershade::cli {
namespace {

std::string shown_default(const ParameterDoc& p) {
  return p.default_value.empty() ? "" : " [default " + p.default_value + "]";
}

// Where an experiment gives the procedure.
std::string given_as(const procedures::ProcedureType& p) {
  return p.study() == procedures::Study::adjustment
             ? "the experiment's \"adjust\" block"
             : "a \"forced_choice\" block's \"procedure\": {\"type\": \"" + p.name() + "\", …}";
}

void print_procedure(const procedures::ProcedureType& p) {
  std::printf("%s: %s\n  given as %s\n", p.name().c_str(), p.summary().c_str(),
              given_as(p).c_str());
  for (const auto& d : p.parameter_docs())
    std::printf("  %-20s %s%s\n", d.key.c_str(), d.help.c_str(), shown_default(d).c_str());
  std::printf("\n");
}

// Text for a Markdown table cell: a '|' would end the cell.
std::string cell(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

// The table docs/forced-choice.md shows (DocumentedParameters.TheDocsTablesAreTheProcedures…).
void print_markdown(const procedures::ProcedureType& p) {
  if (p.study() == procedures::Study::adjustment)
    std::printf("The experiment's `\"adjust\"` block: %s.\n", cell(p.summary()).c_str());
  else
    std::printf("`{\"type\": \"%s\", …}`: %s.\n", p.name().c_str(), cell(p.summary()).c_str());
  if (p.parameter_docs().empty()) return;
  std::printf("\n| key | default | meaning |\n|---|---|---|\n");
  for (const auto& d : p.parameter_docs())
    std::printf("| `%s` | %s | %s |\n", d.key.c_str(),
                d.default_value.empty() ? "" : ("`" + d.default_value + "`").c_str(),
                cell(d.help).c_str());
}

}  // namespace

void add_procedures_command(CLI::App& app) {
  auto name = std::make_shared<std::string>();
  auto markdown = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand(
      "procedures",
      "List the procedures (adjustment, forced choice) and the parameters each takes.");
  cmd->add_option("name", *name, "Show only this procedure");
  cmd->add_flag("--markdown", *markdown,
                "As Markdown: the tables of docs/forced-choice.md and docs/adjustment-study.md");
  cmd->callback([name, markdown] {
    const auto show = [&](const procedures::ProcedureType& p) {
      *markdown ? print_markdown(p) : print_procedure(p);
    };
    if (!name->empty()) return show(procedures::procedure_named(*name, "procedures"));
    for (const auto& n : procedures::procedure_names()) {
      if (*markdown) std::printf("### `%s`\n\n", n.c_str());
      show(*procedures::find_procedure(n));
      if (*markdown) std::printf("\n");
    }
  });
  cmd->footer(
      "The adjustment procedure is the experiment's \"adjust\" block. In a forced_choice block: "
      "\"procedure\": {\"type\": NAME, its parameters}, "
      "e.g.\n"
      "{\"type\": \"staircase\", \"startVal\": 1.0, \"stepSizes\": [0.4, 0.2], \"nDown\": 2}.\n"
      "The same object as a file of its own: countershade simulate --procedure P.json "
      "--responses R.csv -o OUT.csv");
}

}  // namespace countershade::cli
