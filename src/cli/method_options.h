#pragma once
// The command-line side of enhancement methods: --method and --lambda are options of the command;
// every other "--name value" is collected into a ParameterBag for the method's own parser, so a
// flag the method does not take is an error naming the method and the flag.

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "enhance/method.h"

namespace countershade::cli {

struct MethodArgs {
  std::string method;  // empty: the unenhanced rendering
  double lambda = 1.0;
};

struct ResolvedMethod {
  const EnhancementMethod* method = nullptr;
  std::shared_ptr<const MethodParameters> parameters;
  RenderRequest request;
};

// Adds --method and --lambda, and lets the command collect the method's parameters.
void add_method_options(CLI::App* cmd, MethodArgs& args, const std::string& method_help);

// The method and its parameters from the command's extra words. Throws InputError.
ResolvedMethod resolve_method(const CLI::App* cmd, const MethodArgs& args);

// A help footer listing each method's parameters (details: `countershade methods`).
std::string method_parameters_help();

// Writes the prepared method's auxiliary images as EXR into `dir`.
void write_auxiliary(const std::string& dir, const PreparedEnhancement& prepared);

}  // namespace countershade::cli
