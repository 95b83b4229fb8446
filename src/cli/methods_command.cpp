// `countershade methods`: what each enhancement method does and the parameters it takes.

#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "core/error.h"
#include "core/parameters.h"
#include "enhance/registry.h"

namespace countershade::cli {
namespace {

void print_method(const EnhancementMethod& m) {
  const MethodAxes axes = m.axes();
  std::printf("%s: %s\n", m.name().c_str(), m.summary().c_str());
  std::printf("  λ (--lambda): %s\n", axes.strength_help.c_str());
  for (const auto& w : axes.widths)
    std::printf("  σ as %-15s %s (%s)\n", (w.key + ":").c_str(), w.help.c_str(), w.unit.c_str());
  for (const auto& p : m.parameter_docs())
    std::printf("  --%-18s %s%s\n", kebab_case(p.key).c_str(), p.help.c_str(),
                p.default_value.empty() ? "" : (" [default " + p.default_value + "]").c_str());
  std::printf("\n");
}

// Text for a Markdown table cell: a '|' would end the cell.
std::string cell(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

// The method's axes and parameters as docs/enhancement-methods.md shows them: the docs' tables
// are this output (DocumentedParameters.TheDocsTablesAreTheMethodsMarkdown).
void print_markdown(const EnhancementMethod& m) {
  const MethodAxes axes = m.axes();
  std::printf("λ: %s.", cell(axes.strength_help).c_str());
  if (axes.widths.empty()) std::printf(" No σ axis.");
  for (size_t i = 0; i < axes.widths.size(); ++i)
    std::printf("%s`%s` (%s): %s", i == 0 ? " σ is one of " : "; ", axes.widths[i].key.c_str(),
                axes.widths[i].unit.c_str(), cell(axes.widths[i].help).c_str());
  std::printf("%s\n", axes.widths.empty() ? "" : ".");
  if (m.parameter_docs().empty()) return;
  std::printf("\n| key | flag | default | meaning |\n|---|---|---|---|\n");
  for (const auto& p : m.parameter_docs())
    std::printf("| `%s` | `--%s` | %s | %s |\n", p.key.c_str(), kebab_case(p.key).c_str(),
                p.default_value.empty() ? "" : ("`" + p.default_value + "`").c_str(),
                cell(p.help).c_str());
}

}  // namespace

void add_methods_command(CLI::App& app) {
  auto name = std::make_shared<std::string>();
  auto markdown = std::make_shared<bool>(false);
  CLI::App* cmd =
      app.add_subcommand("methods", "List the enhancement methods, their axes and parameters.");
  cmd->add_option("name", *name, "Show only this method");
  cmd->add_flag("--markdown", *markdown, "As Markdown: the tables of docs/enhancement-methods.md");
  cmd->callback([name, markdown] {
    const auto show = [&](const EnhancementMethod& m) {
      *markdown ? print_markdown(m) : print_method(m);
    };
    if (!name->empty()) return show(method_named(*name, "methods"));
    for (const auto& n : method_names()) {
      if (*markdown) std::printf("### `%s`\n\n", n.c_str());
      show(*find_method(n));
      if (*markdown) std::printf("\n");
    }
  });
  cmd->footer(
      "In an experiment file the same parameters are keys of a method's entry (snake_case), and σ "
      "is a list\n"
      "under one of the width keys, e.g. {\"method\": \"usm3d\", \"sigma\": [0.03, 0.06], "
      "\"ring_samples\": 3}.\n"
      "On the command line: countershade render SCENE -o OUT.png --method usm3d --lambda 1.5 "
      "--sigma 0.05");
}

}  // namespace countershade::cli
