// `countershade mesh-usm`: 3D unsharp masking of a coloured mesh's vertex colours (a
// MeshLab-style tool for scanned coloured meshes). Vertices, positions and faces are kept;
// only the colours change.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "cli/commands.h"
#include "core/atomic_file.h"
#include "core/color.h"
#include "core/error.h"
#include "core/progress.h"
#include "enhance/usm3d.h"
#include "mesh/colored_mesh.h"
#include "mesh/smoothing.h"
#include "mesh/surface_graph.h"

namespace countershade::cli {
namespace {

namespace fs = std::filesystem;

struct MeshUsmArgs {
  std::string input, output;
  double lambda = std::nan("");
  std::optional<double> sigma;
  std::optional<int> iterations;
  bool no_adapt = false;
  std::string smoothing = "chebyshev";
  std::string ply_format = "binary";
};

void check_arguments(const MeshUsmArgs& args) {
  if (!std::isfinite(args.lambda)) throw InputError("--lambda: must be a finite number");
  if (args.sigma.has_value() == args.iterations.has_value())
    throw InputError("mesh-usm: give exactly one of --sigma or --iterations");
  if (args.sigma && !(*args.sigma > 0 && std::isfinite(*args.sigma)))
    throw InputError("--sigma: must be a positive, finite world-space length");
  if (args.iterations && (*args.iterations < 1 || *args.iterations > kMaxSmoothingIterations))
    throw InputError(
        "--iterations: must be between 1 and 1000000 (a million 1-ring steps take minutes "
        "already)");
  check_output_file(fs::path(args.output), {".ply"}, "a .ply file (it carries vertex colours)");
}

// Applies Δ = λ·gain·(L − smoothed L) to each vertex's lightness (hue and saturation kept);
// vertices with Δ = 0 keep their stored colour exactly. Returns the number of clipped vertices.
size_t apply_contrast(std::vector<glm::dvec3>& colors, const std::vector<Lab>& lab,
                      const SurfaceContrast& sc, double lambda) {
  size_t clipped = 0;
  for (size_t v = 0; v < colors.size(); ++v) {
    const double delta = lambda * sc.gain_factor[v] * (sc.lightness[v] - sc.smooth_lightness[v]);
    if (delta == 0.0) continue;
    const double target = lab[v].L + delta;
    const glm::dvec3 rgb = lab_to_linear_rgb(with_lightness(lab[v], target));
    bool clip = target < 0 || target > 100;
    for (int c = 0; c < 3; ++c) {
      clip |= rgb[c] < -1e-9 || rgb[c] > 1 + 1e-9;
      colors[v][c] = srgb_encode(std::clamp(rgb[c], 0.0, 1.0));
    }
    clipped += clip;
  }
  return clipped;
}

// The share of a large mesh's run done after each step (reading and building the connectivity
// take about a third, smoothing a fifth, writing the rest: docs/performance.md, "Large meshes").
constexpr double kRead = 0.35, kSmoothed = 0.7, kComposed = 0.75;

void run(const MeshUsmArgs& args) {
  check_arguments(args);
  Progress progress("mesh-usm");
  ColoredMeshFile mesh = ColoredMeshFile::read(args.input);
  progress.update(kRead);
  std::vector<glm::dvec3> colors = mesh.colors();
  std::vector<Lab> lab(colors.size());
  std::vector<double> lightness(colors.size());
  for (size_t v = 0; v < colors.size(); ++v) {
    lab[v] = srgb_to_lab(colors[v]);
    lightness[v] = lab[v].L;
  }
  const SmoothingWidth width{
      args.sigma, args.iterations, !args.no_adapt,
      args.smoothing == "chebyshev" ? SmoothingScheme::chebyshev : SmoothingScheme::iterate};
  // The 1-ring of the triangulated mesh, as rendering sees it, with vertices welded at seams.
  const std::vector<glm::vec3> positions = mesh.positions();
  const SurfaceContrast sc = surface_contrast(
      surface_graph(positions, triangulated_edges(mesh.polygons())), lightness, {}, width);
  progress.update(kSmoothed);
  const size_t clipped = apply_contrast(colors, lab, sc, args.lambda);
  mesh.set_colors(colors);
  progress.update(kComposed);
  mesh.write(fs::path(args.output),
             args.ply_format == "ascii" ? PlyEncoding::ascii : PlyEncoding::binary);
  const int most = *std::max_element(sc.iterations.begin(), sc.iterations.end());
  progress.finish("wrote " + args.output + " (" + std::to_string(colors.size()) + " vertices, " +
                  std::to_string(sc.components.count) + " components, up to " +
                  std::to_string(most) + " iterations, " + std::to_string(clipped) +
                  " clipped vertices)");
}

}  // namespace

void add_mesh_usm_command(CLI::App& app) {
  auto args = std::make_shared<MeshUsmArgs>();
  CLI::App* cmd = app.add_subcommand("mesh-usm",
                                     "3D unsharp masking of a coloured mesh's vertex colours; "
                                     "writes the same mesh with new colours.");
  cmd->add_option("input", args->input, "Mesh with vertex colours (PLY, OFF or OBJ)")->required();
  cmd->add_option("-o,--output", args->output, "Output mesh (.ply)")->required();
  cmd->add_option("--lambda", args->lambda, "Enhancement strength λ")->required();
  cmd->add_option("--sigma", args->sigma, "Smoothing width σ in the mesh's units");
  cmd->add_option("--iterations", args->iterations,
                  "Explicit number of smoothing iterations instead of σ");
  cmd->add_flag("--no-adapt", args->no_adapt, "Constant gain λ (no √(1+Var) adaptation)");
  cmd->add_option("--smoothing", args->smoothing,
                  "chebyshev: the n 1-ring steps in O(√n) products, within 1e-7 of the range; "
                  "iterate: one product per step")
      ->check(CLI::IsMember({"chebyshev", "iterate"}))
      ->capture_default_str();
  cmd->add_option("--ply-format", args->ply_format,
                  "binary: little-endian, about half the size; ascii: text, each float in the "
                  "fewest digits that read back to it")
      ->check(CLI::IsMember({"binary", "ascii"}))
      ->capture_default_str();
  cmd->callback([args] { run(*args); });
  cmd->footer(
      "Example:\n  countershade mesh-usm scan.ply -o scan-enhanced.ply --lambda 1.5 --sigma 0.01");
}

}  // namespace countershade::cli
