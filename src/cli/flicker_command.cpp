// `countershade flicker`: how much an enhancement changes from frame to frame of an animated
// scene at the surface points both frames see (docs/enhancement-methods.md, "Flicker").

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>

#include "cli/commands.h"
#include "render/frame_range.h"
#include "cli/method_options.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/false_colour.h"
#include "core/image.h"
#include "core/progress.h"
#include "enhance/lightness.h"
#include "render/scene_animation.h"
#include "stimuli/perspective_coherence.h"

namespace countershade::cli {
namespace {

struct FlickerArgs {
  std::string scene, frames, csv, maps;
  MethodArgs method;
  std::optional<int> spp, threads;
};

struct Frame {
  std::shared_ptr<const View> view;
  std::vector<float> layer, plain;  // enhanced − plain L*, and plain L*
};

Frame render_frame(const Scene& base, int frame, const ResolvedMethod& m, const FlickerArgs& args) {
  auto scene = std::make_shared<const Scene>(scene_at(base, base.animation->time_of(frame)));
  ViewPlan plan;
  plan.uses.push_back({m.method, m.parameters, nlohmann::json::object()});
  plan.max_abs_lambda = std::abs(args.method.lambda);
  ViewOptions options;
  options.threads = args.threads.value_or(0);
  Frame f;
  f.view = render_view(scene, plan, options);
  const auto prepared = m.method->prepare(make_use_context(f.view, 0, options.threads), *m.parameters);
  f.layer = enhancement_layer(*f.view, prepared->compose(args.method.lambda).display);
  f.plain = view_lightness(*f.view);
  return f;
}

// |ΔE| per pixel in false colour, 0 … 5 L* (NaN, where a pixel did not count: black).
void write_map(const std::string& dir, int frame, const std::vector<float>& differences, const View& view) {
  Image values(view.width(), view.height(), 1);
  for (size_t i = 0; i < differences.size(); ++i) values.pixels[i] = differences[i] / 5.0f;
  char name[32];
  std::snprintf(name, sizeof name, "flicker-%04d.png", frame);
  write_image(std::filesystem::path(dir) / name, false_colour_image(values));
}

// The pair (frame − 1, frame): surface points carried along their objects' motion.
std::pair<Reprojection, Reprojection> compare(const Scene& base, const Frame& a, const Frame& b, int frame,
                                              const std::string& maps) {
  const CarryPoint carry = carry_between_frames(base, frame - 1, frame);
  std::vector<float> differences;
  const Reprojection layer = reprojection_rms(*a.view, a.layer, *b.view, b.layer, carry, maps.empty() ? nullptr : &differences);
  if (!maps.empty()) write_map(maps, frame, differences, *a.view);
  return {layer, reprojection_rms(*a.view, a.plain, *b.view, b.plain, carry)};
}

void run(const FlickerArgs& args, const CLI::App* cmd) {
  const ResolvedMethod m = resolve_method(cmd, args.method);
  if (!args.csv.empty()) check_output_file(args.csv, {".csv"}, ".csv");
  if (!args.maps.empty()) {
    check_output_folder(args.maps);
    std::filesystem::create_directories(args.maps);
  }
  Scene base = load_scene(args.scene);
  apply_request(base, m.request);
  if (args.spp) base.settings.spp = *args.spp;
  m.method->check_scene(base, *m.parameters);
  const auto [first, last] = frame_range(args.frames, base, 1, "--frames");
  std::ostringstream csv;
  csv << "frame,flicker_lstar,plain_reprojection_lstar,pixels\n";
  Progress progress("flicker");
  double sum = 0, plain_sum = 0;
  Frame previous = render_frame(base, first, m, args);
  for (int f = first + 1; f <= last; ++f) {
    Frame current = render_frame(base, f, m, args);
    const auto [flicker, plain] = compare(base, previous, current, f, args.maps);
    csv << f << ',' << flicker.rms << ',' << plain.rms << ',' << flicker.pixels << '\n';
    sum += flicker.rms;
    plain_sum += plain.rms;
    previous = std::move(current);
    progress.update(double(f - first) / double(last - first));
  }
  if (!args.csv.empty()) write_text_atomically(args.csv, csv.str());
  char line[256];
  std::snprintf(line, sizeof line, "%d frame pairs, mean flicker %.4f L* (the plain render's own reprojection %.4f L*)",
                last - first, sum / (last - first), plain_sum / (last - first));
  progress.finish(line);
}

}  // namespace

void add_flicker_command(CLI::App& app) {
  auto args = std::make_shared<FlickerArgs>();
  CLI::App* cmd = app.add_subcommand(
      "flicker", "Measure how an enhancement changes between the frames of an animated scene, in L* per frame.");
  cmd->add_option("scene", args->scene, "Scene description with an animation (docs/scene-format.md)")->required();
  add_method_options(cmd, args->method, "Enhancement method");
  cmd->add_option("--frames", args->frames, "Frames A:B (default: all)");
  cmd->add_option("--csv", args->csv, "Write frame, flicker, the plain render's reprojection error and pixels per pair");
  cmd->add_option("--maps", args->maps,
                  "Write |change| per pixel of each pair as DIR/flicker-NNNN.png (viridis over 0–5 L*; black: not counted)");
  cmd->add_option("--spp", args->spp, "A fixed number of samples per pixel instead of the noise budget")->check(CLI::Range(1, 65536));
  cmd->add_option("--threads", args->threads, "Worker threads (default: all cores)")->check(CLI::Range(1, 1024));
  cmd->callback([cmd, args] { run(*args, cmd); });
  cmd->footer(method_parameters_help() +
              "\nExample:\n"
              "  countershade flicker orbit.json --method usm2d --sigma-px 3 --lambda 1 --csv usm2d.csv");
}

}  // namespace countershade::cli
