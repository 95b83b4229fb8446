#include "render/render_request.h"

#include <algorithm>

#include "core/error.h"

namespace countershade {

void RenderRequest::merge(const RenderRequest& other, const std::string& who) {
  scene |= other.scene;
  depth |= other.depth;
  vertex_radiance |= other.vertex_radiance;
  renders_again |= other.renders_again;
  ring_samples = std::max(ring_samples, other.ring_samples);
  if (other.refine_edge_length) {
    if (refine_edge_length && *refine_edge_length != *other.refine_edge_length)
      throw_input_error(
          who,
          "asks to refine the scene's meshes to a different edge length than another method "
          "of the same scene (one view serves them all)");
    refine_edge_length = other.refine_edge_length;
  }
}

}  // namespace countershade
