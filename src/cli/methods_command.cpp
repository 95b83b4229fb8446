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

}  // namespace

void add_methods_command(CLI::App& app) {
  auto name = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("methods", "List the enhancement methods, their axes and parameters.");
  cmd->add_option("name", *name, "Show only this method");
  cmd->callback([name] {
    if (!name->empty()) return print_method(method_named(*name, "methods"));
    for (const auto& n : method_names()) print_method(*find_method(n));
  });
  cmd->footer(
      "In an experiment file the same parameters are keys of a method's entry (snake_case), and σ is a list\n"
      "under one of the width keys, e.g. {\"method\": \"usm3d\", \"sigma\": [0.03, 0.06], \"ring_samples\": 3}.\n"
      "On the command line: countershade render SCENE -o OUT.png --method usm3d --lambda 1.5 --sigma 0.05");
}

}  // namespace countershade::cli
