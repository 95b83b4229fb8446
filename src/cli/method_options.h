#pragma once
// Command-line options shared by the commands that apply an enhancement method.

#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "enhance/method.h"

namespace countershade::cli {

struct MethodArgs {
  std::string method = "none";
  double lambda = 1.0;
  MethodOptions options;
  std::string kernel;  // "5%" or "5"
  std::string cold, warm;
  bool no_adapt = false;
};

// Adds --lambda and the image-space options (kernel, σ, depth-usm operator and its settings).
void add_image_method_options(CLI::App* cmd, MethodArgs& args);

// Parses the string-valued options into args.options, checks λ and the method's options.
// Throws InputError with the option's name.
const EnhancementMethod& resolve_method(MethodArgs& args);

// Writes the prepared method's auxiliary images as EXR into `dir`.
void write_auxiliary(const std::string& dir, const PreparedEnhancement& prepared);

}  // namespace countershade::cli
