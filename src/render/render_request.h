#pragma once
// What an enhancement method needs from rendering. A stimulus set merges the requests of every
// method applied to a scene, renders that scene once, and gives every method the same view.

#include <memory>
#include <optional>
#include <string>

#include "render/hooks.h"

namespace countershade {

struct RenderRequest {
  bool scene = false;            // works on a rendered scene (meshes, hits), not on any image
  bool depth = false;            // reads a depth map (rendered, or given with an external image)
  bool vertex_radiance = false;  // the outgoing radiance at every mesh vertex
  int ring_samples = 0;          // per-vertex anti-aliasing: samples per incident triangle
  std::optional<double> refine_edge_length;  // split longer mesh edges before rendering
  // Renders the scene again with hooks (per λ): the base render keeps its rays' answers so that
  // those renders re-shade instead of tracing (render/trace_log.h).
  bool renders_again = false;
  // Hooks for renders the method asks for itself (PrepareContext::render_again); the base view of
  // a stimulus set is always rendered without them.
  std::shared_ptr<const ShadingHook> shading_hook;
  std::shared_ptr<const TextureHook> texture_hook;

  // The union of two requests. Two different refinements of one scene cannot both be honoured:
  // InputError naming `who`.
  void merge(const RenderRequest& other, const std::string& who);
};

}  // namespace countershade
