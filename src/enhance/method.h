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

// Everything rendered once per view.
struct View {
  const Scene* scene = nullptr;
  RenderResult render;    // radiance, G-buffer and (for methods that need it) vertex radiance
  Image display;          // display-encoded code values in [0,1], the unenhanced stimulus
  std::vector<Lab> lab;   // CIELAB of `display`, per pixel
};

// Builds the View: encodes the render for display and converts it to CIELAB.
View make_view(const Scene& scene, RenderResult render);

// Options of all methods in one plain struct; each method reads the fields it uses and
// `validate` rejects the ones it cannot use.
struct MethodOptions {
  // usm3d
  std::optional<double> sigma;           // world units
  std::optional<double> sigma_fraction;  // of the scene's bounding-box diagonal
  std::optional<int> iterations;         // explicit smoothing iterations instead of σ
  bool adapt = true;                     // adaptive gain √(1 + Var)
};

class PreparedEnhancement {
 public:
  virtual ~PreparedEnhancement() = default;
  // The enhanced stimulus for strength λ.
  virtual Composed compose(double lambda) const = 0;
  // Parameters worth recording (e.g. smoothing iterations per object), as JSON.
  virtual nlohmann::json parameters() const { return nlohmann::json::object(); }
};

class EnhancementMethod {
 public:
  virtual ~EnhancementMethod() = default;
  virtual std::string name() const = 0;
  virtual std::string summary() const = 0;
  // Whether make_view must include per-vertex radiance.
  virtual bool needs_vertex_radiance() const { return false; }
  // Throws InputError for options this method cannot use (missing σ, σ ≤ 0, ...).
  virtual void validate(const MethodOptions& options) const = 0;
  // The once-per-(view, σ) work.
  virtual std::unique_ptr<PreparedEnhancement> prepare(const View& view, const MethodOptions& options) const = 0;
};

// nullptr when no method has that name.
const EnhancementMethod* find_method(const std::string& name);
std::vector<std::string> method_names();

}  // namespace countershade
