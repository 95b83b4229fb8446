#pragma once
// Flicker (docs/enhancement-methods.md, "Flicker"): how much an enhancement changes from one frame
// of an animated scene to the next, at the surface points both frames see. The later frame is
// reprojected into the earlier through the frames' geometry and the objects' motion
// (reprojection_rms). The `flicker` command (frames rendered in memory) and a stimulus set's
// sequences (frames read from its files, stimuli/sequence_flicker.h) both measure it here.

#include <array>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "enhance/method.h"
#include "enhance/view.h"
#include "measures/perspective_coherence.h"
#include "render/scene.h"

namespace countershade {

// One frame as the measure reads it.
struct FlickerFrame {
  std::shared_ptr<const View> view;     // its geometry (depth, objects, camera)
  std::span<const float> layer, plain;  // enhanced − plain L*, and plain L*
  // Optional planes: enhanced − plain per channel in levels of 8-bit output
  // (FlickerOptions::object), and the layer and plain L* blurred (FlickerOptions::scale_px).
  std::array<std::vector<float>, 3> levels;
  std::vector<float> layer_at_scale, plain_at_scale;
  std::vector<char>
      region;  // FlickerOptions' region when given by another scene (empty: from `view`)
};

// The measures beyond the layer's RMS.
struct FlickerOptions {
  double scale_px = 0;  // > 0: also the layers blurred with a Gaussian of this σ in pixels
  double stable = 0;    // > 0: also over the pixels whose plain L* reprojects within this many L*
  int object = -1;      // ≥ 0: also how much the enhancement of this object's pixels changes
  // A region of the earlier frame (when `on` or `near` is ≥ 0): the pixels of object `on` (any
  // object when −1) within `within_px` of a pixel of object `near` (anywhere when −1). The RMS of
  // the layer and of the plain L* are then also taken over it, e.g. a floor beside an occluder.
  int on = -1, near = -1;
  double within_px = 40;
  // The scene whose geometry gives the region (null: each frame's own), e.g. the scene with an
  // occluder that the measured one leaves out, so that both measure the same pixels.
  const Scene* region_scene = nullptr;
  bool has_region() const { return on >= 0 || near >= 0; }
};

// The pixels of FlickerOptions' region in `view` (1: in it).
std::vector<char> region_pixels(const View& view, const FlickerOptions& options);

// A frame's geometry as a View without pixels (depth, objects, camera): what the reprojection
// and the region read.
std::shared_ptr<const View> geometry_view(std::shared_ptr<const Scene> scene, int threads);

// How much the enhancement of one object's pixels changes between two frames, in levels of 8-bit
// output (at any bit depth): per pixel the largest change over the three channels.
struct ObjectChange {
  double max = 0, p99 = 0;
  size_t pixels = 0;
};

// The plain render's own change between two frames: what even an enhancement attached to the
// surface would show. Its per-pixel differences pick the stable pixels.
struct PlainChange {
  Reprojection rms;
  std::vector<float> differences;  // NaN where a pixel did not count
};
PlainChange plain_change(const FlickerFrame& a, const FlickerFrame& b, const CarryPoint& carry);

// The measures of one frame pair.
struct PairFlicker {
  Reprojection layer;              // the layer's RMS change
  std::vector<float> differences;  // the layer's per pixel (NaN where a pixel did not count)
  Reprojection stable;             // FlickerOptions::stable
  double at_scale = 0, plain_at_scale = 0;  // FlickerOptions::scale_px
  ObjectChange object, object_stable;       // FlickerOptions::object (object_stable: with stable)
  Reprojection region, plain_region;  // FlickerOptions' region: the layer's and the plain L*'s
};
PairFlicker pair_flicker(const FlickerFrame& a, const FlickerFrame& b, const CarryPoint& carry,
                         const PlainChange& plain, const FlickerOptions& options);

// What is measured of a method: its layer (enhanced − plain L*) or its mask
// (PreparedEnhancement::mask, the low-pass signal the layer is taken against).
enum class FlickerComponent { layer, mask };

// What the `flicker` command renders: one method at one λ, frames at a bit depth.
struct FlickerRender {
  const EnhancementMethod* method = nullptr;
  std::shared_ptr<const MethodParameters> parameters;
  double lambda = 1;
  int bits = 8;
  int threads = 0;
  FlickerComponent component = FlickerComponent::layer;
};

// Per frame pair, the pair's frame number, both frames, the plain change and its measures.
using FlickerPairSink =
    std::function<void(int frame, const FlickerFrame& previous, const FlickerFrame& current,
                       const PlainChange& plain, const PairFlicker& pair)>;

// Renders frames first … last of `base` (which must have an animation) with the method and
// measures each consecutive pair. `progress`: the share of pairs done.
void measure_rendered_flicker(const Scene& base, int first, int last, const FlickerRender& render,
                              const FlickerOptions& options, const FlickerPairSink& sink,
                              const std::function<void(double)>& progress = {});

// The index of the object called `name` (−1 for an empty name). Throws InputError naming `option`.
int named_object(const Scene& scene, const std::string& name, const char* option);

// The scene without the object called `name`, and without its motion: the flicker that remains
// when, say, a moving occluder is taken out. Throws InputError.
void remove_object(Scene& scene, const std::string& name);

}  // namespace countershade
