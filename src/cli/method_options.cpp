#include "cli/method_options.h"

#include <cmath>
#include <filesystem>

#include "core/error.h"
#include "core/image.h"
#include "core/parameters.h"
#include "enhance/registry.h"

namespace countershade::cli {

void add_method_options(CLI::App* cmd, MethodArgs& args, const std::string& method_help) {
  cmd->add_option("--method", args.method, method_help + " (default: the unenhanced rendering)");
  cmd->add_option("--lambda", args.lambda, "Enhancement strength λ (0 = unenhanced)")
      ->capture_default_str();
  cmd->allow_extras();  // the method's own parameters
}

ResolvedMethod resolve_method(const CLI::App* cmd, const MethodArgs& args) {
  ResolvedMethod r;
  r.method = args.method.empty() ? &unenhanced_method() : &method_named(args.method, "--method");
  if (!std::isfinite(args.lambda)) throw InputError("--lambda: must be a finite number");
  ParameterBag bag = ParameterBag::from_arguments(cmd->remaining());
  r.parameters = r.method->parse(bag);
  r.request = r.method->request(*r.parameters);
  return r;
}

std::string method_parameters_help() {
  std::string text = "Method parameters (--name value; `countershade methods` explains them):\n";
  for (const auto& name : method_names()) {
    const EnhancementMethod& m = *find_method(name);
    std::string line = "  " + name + ":";
    if (m.parameter_docs().empty()) line += " none";
    for (const auto& doc : m.parameter_docs()) line += " --" + kebab_case(doc.key);
    text += line + "\n";
  }
  return text;
}

void write_auxiliary(const std::string& dir, const PreparedEnhancement& prepared) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw_input_error(dir, "cannot create folder (" + ec.message() + ")");
  for (const auto& [name, image] : prepared.auxiliary())
    write_image(std::filesystem::path(dir) / (name + ".exr"), image);
}

}  // namespace countershade::cli
