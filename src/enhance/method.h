#pragma once
// The interface every enhancement method implements, and the registry that finds them by name.
//
// Heavy work happens once: the renderer produces a View (image, G-buffer, per-vertex radiance)
// once per camera; a method prepares it once per width parameter (σ); the prepared state then
// composes any number of strengths λ cheaply. Adding a method means one file that implements
// EnhancementMethod and one line in method.cpp's registry.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/color.h"
#include "core/image.h"
#include "enhance/lightness.h"
#include "render/renderer.h"
#include "render/scene.h"

namespace countershade {

// Everything produced once per view: by the renderer, or read from an image (+ depth) file.
struct View {
  const Scene* scene = nullptr;  // null for external images
  DisplayEncoding encoding = DisplayEncoding::srgb();
  RenderResult render;        // G-buffer and vertex radiance (renders only)
  std::vector<float> depth;   // linear eye depth per pixel; 0, inf or NaN = background/invalid
  Image display;              // the unenhanced stimulus: code values in [0,1], quantised to `bits`
  std::vector<Lab> lab;       // CIELAB of `display`, per pixel
  int bits = 8;

  int width() const { return display.width; }
  int height() const { return display.height; }
};

// Builds the View of a render: exposure and display encoding, quantised to the output bit depth
// (8 or 16) so every method starts from exactly the pixels of the reference image, then CIELAB.
View make_view(const Scene& scene, RenderResult render, int bits = 8);

// The View of an external image (display-encoded code values, 3 channels) with an optional
// depth map of the same size.
View make_image_view(Image display, std::vector<float> depth, const DisplayEncoding& encoding, int bits);

// Rounds code values to the nearest n-bit level (kept as floats).
void quantize_in_place(Image& image, int bits);

// Options of all methods in one plain struct; each method reads the fields it uses and
// `validate` rejects the ones it cannot use.
struct MethodOptions {
  // usm3d
  std::optional<double> sigma;           // world units
  std::optional<double> sigma_fraction;  // of the scene's bounding-box diagonal
  std::optional<int> iterations;         // explicit smoothing iterations instead of σ
  bool adapt = true;                     // adaptive gain √(1 + Var)

  // usm2d and depth-usm: image-space width, exactly one of
  std::optional<double> kernel_percent;  // kernel size K as % of the image diagonal, σ_px = K/4
  std::optional<double> sigma_px;        // σ in pixels
  std::optional<double> sigma_percent;   // σ as % of the image diagonal

  // depth-usm
  std::string op = "darken";             // add | contrast | darken | color
  std::string contrast = "stretch";      // C for `contrast`: stretch | equalize | local
  std::string space = "rgb";             // rgb (as in Luft et al.) | lab (lightness only)
  std::string depth_mapping = "linear";  // linear eye depth | zbuffer (non-linear, near/far)
  std::optional<double> z_near, z_far;   // zbuffer planes (default: the valid depth range)
  glm::dvec3 cold{-0.1, -0.05, 0.15}, warm{0.15, 0.1, -0.1};

  // cornsweet: the width comes from sigma_px (image mode) or sigma (surface mode)
  std::string cornsweet_mode = "image";
  double cornsweet_amplitude = 4.0;  // ΔL* per unit of λ
  glm::dvec3 edge_point{0.0}, edge_direction{1, 0, 0}, bright_normal{0, 0, 1};
};

// σ in pixels for an image of the given size from the image-space options (0 if none is given).
double image_sigma_px(const MethodOptions& options, int width, int height);

class PreparedEnhancement {
 public:
  virtual ~PreparedEnhancement() = default;
  // The enhanced stimulus for strength λ.
  virtual Composed compose(double lambda) const = 0;
  // Parameters worth recording (e.g. smoothing iterations per object), as JSON.
  virtual nlohmann::json parameters() const { return nlohmann::json::object(); }
  // Intermediate images a researcher may want to inspect (name without extension, image).
  virtual std::vector<std::pair<std::string, Image>> auxiliary() const { return {}; }
};

class EnhancementMethod {
 public:
  virtual ~EnhancementMethod() = default;
  virtual std::string name() const = 0;
  virtual std::string summary() const = 0;
  // Whether make_view must include per-vertex radiance (and so a rendered scene).
  virtual bool needs_vertex_radiance() const { return false; }
  // Whether the view must carry a depth map.
  virtual bool needs_depth() const { return false; }
  // Throws InputError for options this method cannot use (missing σ, σ ≤ 0, ...).
  virtual void validate(const MethodOptions& options) const = 0;
  // The once-per-(view, σ) work.
  virtual std::unique_ptr<PreparedEnhancement> prepare(const View& view, const MethodOptions& options) const = 0;
};

// nullptr when no method has that name.
const EnhancementMethod* find_method(const std::string& name);
std::vector<std::string> method_names();

}  // namespace countershade
