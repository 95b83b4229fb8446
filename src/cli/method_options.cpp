#include "cli/method_options.h"

#include <cmath>
#include <filesystem>
#include <sstream>

#include "core/error.h"
#include "core/image.h"

namespace countershade::cli {
namespace {

glm::dvec3 parse_color(const std::string& option, const std::string& text) {
  std::string t = text;
  for (char& c : t)
    if (c == ',') c = ' ';
  std::istringstream in(t);
  glm::dvec3 v;
  if (!(in >> v.x >> v.y >> v.z) || !std::isfinite(v.x + v.y + v.z) || !(in >> std::ws).eof())
    throw InputError(option + ": expected three numbers R,G,B, got '" + text + "'");
  return v;
}

}  // namespace

void add_image_method_options(CLI::App* cmd, MethodArgs& args) {
  cmd->add_option("--lambda", args.lambda, "Enhancement strength λ (0 = unenhanced)")->capture_default_str();
  cmd->add_option("--kernel", args.kernel,
                  "usm2d/depth-usm: kernel size K as % of the image diagonal (σ = K/4), e.g. 5%");
  cmd->add_option("--sigma-px", args.options.sigma_px, "usm2d/depth-usm: Gaussian σ in pixels");
  cmd->add_option("--sigma-percent", args.options.sigma_percent, "usm2d/depth-usm: σ as % of the image diagonal");
  cmd->add_option("--operator", args.options.op, "depth-usm: add | contrast | darken | color")
      ->check(CLI::IsMember({"add", "contrast", "darken", "color"}))
      ->capture_default_str();
  cmd->add_option("--contrast", args.options.contrast, "depth-usm contrast: stretch | equalize | local")
      ->check(CLI::IsMember({"stretch", "equalize", "local"}))
      ->capture_default_str();
  cmd->add_option("--space", args.options.space, "depth-usm: rgb (as published) | lab (lightness only)")
      ->check(CLI::IsMember({"rgb", "lab"}))
      ->capture_default_str();
  cmd->add_option("--depth-mapping", args.options.depth_mapping, "depth-usm: linear eye depth | zbuffer")
      ->check(CLI::IsMember({"linear", "zbuffer"}))
      ->capture_default_str();
  cmd->add_option("--z-near", args.options.z_near, "depth-usm zbuffer: near plane (default: nearest depth)");
  cmd->add_option("--z-far", args.options.z_far, "depth-usm zbuffer: far plane (default: farthest depth)");
  cmd->add_option("--cold", args.cold, "depth-usm color: cold colour R,G,B (default -0.1,-0.05,0.15)");
  cmd->add_option("--warm", args.warm, "depth-usm color: warm colour R,G,B (default 0.15,0.1,-0.1)");
}

const EnhancementMethod& resolve_method(MethodArgs& args) {
  const EnhancementMethod* method = find_method(args.method);
  if (!method) throw InputError("--method: unknown method '" + args.method + "'");
  if (!std::isfinite(args.lambda)) throw InputError("--lambda: must be a finite number");
  if (!args.kernel.empty()) {
    std::string text = args.kernel;
    if (text.back() == '%') text.pop_back();
    try {
      size_t used = 0;
      double value = std::stod(text, &used);
      if (used != text.size() || !std::isfinite(value)) throw std::invalid_argument("");
      args.options.kernel_percent = value;
    } catch (const std::exception&) {
      throw InputError("--kernel: expected a percentage of the image diagonal like 5%, got '" + args.kernel + "'");
    }
  }
  if (!args.cold.empty()) args.options.cold = parse_color("--cold", args.cold);
  if (!args.warm.empty()) args.options.warm = parse_color("--warm", args.warm);
  args.options.adapt = !args.no_adapt;
  method->validate(args.options);
  return *method;
}

void write_auxiliary(const std::string& dir, const PreparedEnhancement& prepared) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw_input_error(dir, "cannot create folder (" + ec.message() + ")");
  for (const auto& [name, image] : prepared.auxiliary())
    write_image(std::filesystem::path(dir) / (name + ".exr"), image);
}

}  // namespace countershade::cli
