#pragma once
// The interface every enhancement method implements (docs/architecture.md, "Methods").
//
// A method owns its parameters: it parses them from a ParameterBag (experiment files and
// command-line flags both become one), rejecting keys it does not use. It declares its axes
// (the strength λ and the width σ with its unit) and what it needs from rendering. Heavy work
// happens once: the view is rendered once per camera, the method prepares it once per σ, and
// the prepared state composes any number of strengths λ cheaply.
//
// Adding a method means one file that implements EnhancementMethod and one line in the
// registry (enhance/registry.cpp).

#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/image.h"
#include "core/parameters.h"
#include "enhance/view.h"
#include "render/render_request.h"
#include "render/sample_field.h"

namespace countershade {

// A method's own parameter struct derives from this.
class MethodParameters {
 public:
  virtual ~MethodParameters() = default;
};

// One way to give the width σ: the key of its value, its unit and what it means.
struct WidthAxis {
  std::string key;   // "sigma", "sigma_px", ...
  std::string unit;  // "world units", "px", "% of the image diagonal", ...
  std::string help;
};

struct MethodAxes {
  std::string strength_help;      // what λ does
  std::vector<WidthAxis> widths;  // the σ alternatives (exactly one is given); empty: no σ
};

struct Composed {
  Image display;  // the stimulus: code values of the view's bit depth, as values in [0,1]
  size_t clipped_pixels = 0;  // pixels where L' left [0,100] or an RGB channel left [0,1]
};

// The sampling noise of a stimulus, per pixel: the standard deviation of its L* between renders
// with other seeds, before quantisation. Empty: the view's own (render.noise).
struct NoiseModel {
  std::vector<float> sigma;
};

// What a method computes from the per-vertex signal before the pixels are sampled: the
// per-sample fields it needs averaged over each pixel (render/sample_field.h).
class SurfaceStage {
 public:
  virtual ~SurfaceStage() = default;
  virtual SampleFields fields() const = 0;
};

class PreparedEnhancement {
 public:
  virtual ~PreparedEnhancement() = default;
  // The enhanced stimulus for strength λ.
  virtual Composed compose(double lambda) const = 0;
  // The stimulus for strength λ with `offset` L* more on every pixel where `where` is 1 (0
  // elsewhere), composed and quantised once: a study design's mean hold (stimuli/mean_hold.h)
  // moves each pixel before its rounding, not whole codes after it. Empty for methods that do not
  // compose in lightness; the caller then offsets the composed stimulus (before its rounding, if
  // the method leaves that to the writer).
  virtual std::optional<Composed> compose_offset(double /*lambda*/, double /*offset*/,
                                                 std::span<const double> /*where*/) const {
    return std::nullopt;
  }
  // Parameters worth recording (e.g. smoothing iterations per object), as JSON.
  virtual nlohmann::json parameters() const { return nlohmann::json::object(); }
  // Intermediate images a researcher may want to inspect (name without extension, image).
  virtual std::vector<std::pair<std::string, Image>> auxiliary() const { return {}; }
  // How the stimulus of strength λ amplifies the view's sampling noise.
  virtual NoiseModel noise(double /*lambda*/) const { return {}; }
  // The low-pass signal M of a method that writes U = S + λ·(S − M), per pixel of the view in L*
  // (docs/enhancement-methods.md, "Mask flicker"); depth-usm gives its importance layer ΔD
  // instead, as 100·ΔD. Empty: the method subtracts no low-pass signal.
  virtual std::vector<float> mask() const { return {}; }
};

// What prepare() may use: the view, this method's surface stage and fields, and a way to render
// the view's scene again with hooks.
struct PrepareContext {
  std::shared_ptr<const View> view;
  std::shared_ptr<const SurfaceStage> stage;      // from surface_stage(), when the method has one
  std::vector<const std::vector<float>*> fields;  // the stage's fields, averaged per pixel
  const ChangeNoise* change_noise = nullptr;  // the render's noise estimate of its change per λ
  int threads = 0;                            // 0 = all cores
  // The caller composes many λ (a stimulus set): a method that would render every λ again may
  // instead compose each from the view's own samples (exact up to rounding, and far cheaper),
  // once the view was sampled for the largest λ. False (`render`): it renders its one λ again,
  // sampled to the noise budget on its own.
  bool compose_from_samples = false;
  // The view's scene rendered again for `request` (its hooks) with the same camera, samples and
  // seed. Its View holds the display and the radiance only (no CIELAB image, G-buffer or noise).
  // Null for external images.
  std::function<std::shared_ptr<const View>(const RenderRequest&)> render_again;
};

// What a surface stage sees: the scene and its render so far (the G-buffer, the vertex signal).
struct SurfaceContext {
  const Scene& scene;
  const RenderResult& render;
  int threads = 0;
};

class EnhancementMethod {
 public:
  virtual ~EnhancementMethod() = default;
  virtual std::string name() const = 0;
  virtual std::string summary() const = 0;
  virtual MethodAxes axes() const = 0;
  virtual std::vector<ParameterDoc> parameter_docs() const = 0;
  // False only for the unenhanced rendering: its output may be linear radiance (EXR).
  virtual bool enhances() const { return true; }

  // The one parser: reads every parameter the method takes (the width included) and ends with
  // bag.finish(name()), so an unused key is an InputError naming the method and the key.
  virtual std::shared_ptr<const MethodParameters> parse(const ParameterBag& bag) const = 0;
  // What the method needs from rendering for these parameters.
  virtual RenderRequest request(const MethodParameters&) const { return {}; }
  // The work between the vertex signal and the pixels (default: none).
  virtual std::shared_ptr<const SurfaceStage> surface_stage(const SurfaceContext&,
                                                            const MethodParameters&) const {
    return nullptr;
  }
  // How the method changes a pixel's L* per unit λ, from a replicate's means and its stage's
  // fields (render/sample_field.h), so that the pixels are sampled until the stimulus meets the
  // noise budget. Default: none (the change does not carry the pixel's noise).
  virtual std::shared_ptr<const ChangePerLambda> change_per_lambda(const MethodParameters&) const {
    return nullptr;
  }
  // For methods that build on the vertex signal (request().vertex_radiance): per object, the L*
  // error its vertices must reach so that the stimulus's share `allowed` of the noise budget holds
  // at |λ| ≤ max_abs_lambda, and how far around the visible surface that matters.
  virtual std::vector<VertexNeed> vertex_needs(const Scene&, const MethodParameters&,
                                               double /*max_abs_lambda*/,
                                               double /*allowed*/) const {
    return {};
  }
  // The folder name of its stimuli in a set, e.g. "depth-usm-darken" (default: the name).
  virtual std::string label(const MethodParameters&) const { return name(); }
  // Checks, before anything renders, that `scene` has what the method needs (e.g. a texture);
  // throws InputError naming the method and what is missing. Default: anything goes.
  virtual void check_scene(const Scene&, const MethodParameters&) const {}
  // The once-per-(view, σ) work. Throws InputError when the view lacks what the method needs.
  virtual std::unique_ptr<PreparedEnhancement> prepare(
      const PrepareContext& context, const MethodParameters& parameters) const = 0;
};

// Casts a method's parameters back to its own struct (parse() made them).
template <class P>
const P& parameters_as(const MethodParameters& p) {
  return static_cast<const P&>(p);
}

// The context of a method that has no surface stage (or of an external image's view).
PrepareContext make_context(std::shared_ptr<const View> view, int threads = 0);
// The context of use `use` of the plan the view was rendered for: its stage and fields.
PrepareContext make_use_context(std::shared_ptr<const View> view, size_t use, int threads = 0);

}  // namespace countershade
