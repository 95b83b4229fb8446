#pragma once
// A view: what the renderer produces once per camera (image, G-buffer, per-vertex radiance), or
// what is read from an image and depth file. Every method of a stimulus set starts from the same
// view; prepared methods share it (std::shared_ptr<const View>) and keep it alive.

#include <memory>
#include <vector>

#include "core/color.h"
#include "core/display.h"
#include "core/image.h"
#include "render/ray_tracer.h"
#include "render/render_request.h"
#include "render/renderer.h"
#include "render/scene.h"

namespace countershade {

// CIELAB per pixel; left unfilled until written (a 1920×1080 view holds 50 MB of it).
using LabPixels = std::vector<Lab, UninitializedAllocator<Lab>>;

struct View {
  std::shared_ptr<const Scene> scene;       // null for external images
  std::shared_ptr<const RayTracer> tracer;  // the scene's BVH, for renders with hooks
  DisplayEncoding encoding = DisplayEncoding::srgb();
  RenderResult render;        // G-buffer and vertex radiance (renders only)
  std::vector<float> depth;   // linear eye depth per pixel; 0, inf or NaN = background/invalid
  Image display;              // the unenhanced stimulus: code values in [0,1], quantised to `bits`
  LabPixels lab;              // CIELAB of `display`, per pixel
  int bits = 8;

  int width() const { return display.width; }
  int height() const { return display.height; }
};

// Rounds code values to the nearest n-bit level (kept as floats).
void quantize_in_place(Image& image, int bits);

// The View of a render: exposure and display encoding, quantised to the output bit depth (8 or
// 16) so every method starts from exactly the pixels of the reference image, then CIELAB.
std::shared_ptr<const View> make_view(std::shared_ptr<const Scene> scene, std::shared_ptr<const RayTracer> tracer,
                                      RenderResult render, int bits = 8);

// The View of an external image (display-encoded code values, 3 channels) with an optional
// depth map of the same size.
std::shared_ptr<const View> make_image_view(Image display, std::vector<float> depth, const DisplayEncoding& encoding,
                                            int bits);

// Applies the request's scene changes (mesh refinement) before the scene is rendered.
void apply_request(Scene& scene, const RenderRequest& request);

struct ViewOptions {
  int bits = 8;
  int threads = 0;
  std::function<void(double)> progress;
};

// Renders a scene for a (merged) request and makes its view.
std::shared_ptr<const View> render_view(std::shared_ptr<const Scene> scene, const RenderRequest& request,
                                        const ViewOptions& options);

}  // namespace countershade
