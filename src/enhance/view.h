#pragma once
// A view: what the renderer produces once per camera (image, G-buffer, per-vertex radiance), or
// what is read from an image and depth file. Every method of a stimulus set starts from the same
// view; prepared methods share it (std::shared_ptr<const View>) and keep it alive.

#include <tbb/task_arena.h>

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/color.h"
#include "core/display.h"
#include "core/image.h"
#include "enhance/display_lab.h"
#include "render/ray_tracer.h"
#include "render/renderer.h"
#include "render/scene.h"

namespace countershade {

class SurfaceStage;
class EnhancementMethod;
class MethodParameters;

// One method with its parameters (one σ of an experiment's method, or a command line's).
struct MethodUse {
  const EnhancementMethod* method = nullptr;
  std::shared_ptr<const MethodParameters> parameters;
  nlohmann::json parameters_json;  // as given, to find the use again (prepare_method)
};

// What methods derive from a view alone and share between their preparations, made once per key.
// A copy of a view starts without them (it may be changed after copying).
class ViewMemo {
 public:
  ViewMemo() = default;
  ViewMemo(const ViewMemo&) {}
  ViewMemo& operator=(const ViewMemo&) { return *this; }
  template <class T>
  std::shared_ptr<const T> get(const std::string& key,
                               const std::function<std::shared_ptr<const T>()>& make) const {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto [entry, first] = values_.try_emplace(key);
    std::shared_ptr<const void>& value = entry->second;
    // Null is kept too: made once, whatever it gives. Isolated, so that a parallel loop inside
    // `make` cannot pick up outer work that asks this memo again while the lock is held.
    if (first) tbb::this_task_arena::isolate([&] { value = make(); });
    return std::static_pointer_cast<const T>(value);
  }

 private:
  mutable std::mutex mutex_;
  mutable std::map<std::string, std::shared_ptr<const void>> values_;
};

struct View {
  std::shared_ptr<const Scene> scene;       // null for external images
  std::shared_ptr<const RayTracer> tracer;  // the scene's BVH, for renders with hooks
  DisplayEncoding encoding = DisplayEncoding::srgb();
  RenderResult render;       // G-buffer and vertex radiance (renders only)
  std::vector<float> depth;  // linear eye depth per pixel; 0, inf or NaN = background/invalid
  Image display;             // the unenhanced stimulus: code values in [0,1], quantised to `bits`
  LabPixels lab;             // CIELAB of `display`, per pixel
  PixelVector lightness;     // L* of `lab` as floats, made with it (the plane image filters read)
  int bits = 8;
  // Per use of the plan the view was rendered for: its surface stage (or null) and the indices of
  // the stage's fields in render.fields.
  std::vector<MethodUse> uses;
  std::vector<std::shared_ptr<const SurfaceStage>> stages;
  std::vector<std::vector<size_t>> stage_fields;
  std::vector<int> change_noise;  // index into render.change_noise, or -1
  ViewMemo memo;

  int width() const { return display.width; }
  int height() const { return display.height; }
  // The object pixel i sees, or -1 where the view has no object ids (external images): then
  // every pixel counts as one surface.
  int object_at(size_t i) const {
    return render.gbuffer.object.size() == depth.size() ? render.gbuffer.object[i] : -1;
  }
};

// Rounds code values to the nearest n-bit level (kept as floats).
void quantize_in_place(Image& image, int bits);

// The View of a render: exposure and display encoding, quantised to the output bit depth (8 or
// 16) so every method starts from exactly the pixels of the reference image, then CIELAB (left
// empty with `lab` false: the renders a method asks for itself, of which it keeps the display).
std::shared_ptr<const View> make_view(std::shared_ptr<const Scene> scene,
                                      std::shared_ptr<const RayTracer> tracer, RenderResult render,
                                      int bits = 8, bool lab = true);

// The View of an external image (display-encoded code values, 3 channels) with an optional
// depth map of the same size, rounded to `bits` unless `round` is false (a stimulus a method has
// not rounded yet, seen with its own L*).
std::shared_ptr<const View> make_image_view(Image display, std::vector<float> depth,
                                            const DisplayEncoding& encoding, int bits,
                                            bool round = true);

}  // namespace countershade
