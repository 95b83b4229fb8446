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
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/image.h"
#include "core/parameters.h"
#include "enhance/view.h"
#include "render/render_request.h"

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

// A documented parameter, for `countershade methods` and --help.
struct ParameterDoc {
  std::string key, default_value, help;
};

struct Composed {
  Image display;              // the stimulus: code values of the view's bit depth, as values in [0,1]
  size_t clipped_pixels = 0;  // pixels where L' left [0,100] or an RGB channel left [0,1]
};

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

// What prepare() may use: the view, and a way to render the view's scene again with hooks.
struct PrepareContext {
  std::shared_ptr<const View> view;
  int threads = 0;  // 0 = all cores
  // The view's scene rendered again for `request` (its hooks) with the same camera, samples and
  // seed. Null for external images.
  std::function<std::shared_ptr<const View>(const RenderRequest&)> render_again;
};

// The context of a view: render_again re-renders its scene (when it has one) at its bit depth.
PrepareContext make_context(std::shared_ptr<const View> view, int threads = 0);

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
  // The folder name of its stimuli in a set, e.g. "depth-usm-darken" (default: the name).
  virtual std::string label(const MethodParameters&) const { return name(); }
  // The once-per-(view, σ) work. Throws InputError when the view lacks what the method needs.
  virtual std::unique_ptr<PreparedEnhancement> prepare(const PrepareContext& context,
                                                       const MethodParameters& parameters) const = 0;
};

// Casts a method's parameters back to its own struct (parse() made them).
template <class P>
const P& parameters_as(const MethodParameters& p) {
  return static_cast<const P&>(p);
}

// Parses a JSON object of parameters for the named method and prepares the view with them: the
// short path for tools and tests. Throws InputError for an unknown method or bad parameters.
std::unique_ptr<PreparedEnhancement> prepare_method(const std::string& method, std::shared_ptr<const View> view,
                                                    const nlohmann::json& parameters, int threads = 0);

}  // namespace countershade
