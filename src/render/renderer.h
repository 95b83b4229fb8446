#pragma once
// One render of a view, in three passes:
//   1. the pixel centres: the G-buffer (depth, normal, ids, which side of a surface is seen);
//   2. on request, the outgoing radiance towards the camera at every mesh vertex, for the side of
//      the surface the pixels show (render/vertex_pass.h);
//   3. the pixels, sampled until each meets the noise budget (render/pixel_pass.h), averaging the
//      per-sample fields that the enhancement methods ask for after seeing pass 2.
// Every sample is a pure function of the seed, so the image does not depend on threads.

#include <vector>

#include "render/ray_tracer.h"
#include "render/render_types.h"
#include "render/scene.h"

namespace countershade {

RenderResult render(const Scene& scene, const RayTracer& tracer, const RenderOptions& options = {});

// Pass 1 alone: the G-buffer of the pixel centres, exactly as `render` makes it (measures that
// need a frame's geometry but not its pixels).
GBuffer render_gbuffer(const Scene& scene, const RayTracer& tracer, int threads = 0);

}  // namespace countershade
