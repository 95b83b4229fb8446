#pragma once
// Evaluating a render's kept shading records again with other hooks (render/trace_log.h).
//
// A render with hooks that replays a log holding every sample's shading record traces nothing: each
// sample is its record evaluated with the hooks. When such a render keeps only its radiance (a
// method's render of one λ), the pixel pass's other work (luminances, coverage, fields, noise and
// the sums they need) is wasted; `replay_radiance` does without it.

#include <optional>

#include "render/render_types.h"
#include "render/scene.h"
#include "render/shading.h"
#include "render/trace_log.h"

namespace countershade {

// One sample whose shading the log kept, evaluated with `shader`'s hooks: its radiance, and for a
// hit its surface point and the side the camera ray saw.
struct ReplayedSample {
  glm::dvec3 radiance{0.0};
  std::optional<SurfacePoint> point;  // none: the ray hit nothing (radiance is its background)
  bool back = false;
};
ReplayedSample replay_sample(const Scene& scene, const Shader& shader, const TraceLog& log,
                             size_t pixel, uint32_t sample);

// The radiance image of a render with `shader`'s hooks at the scene's fixed sample count, when
// `log` holds every sample's shading record: the same bits as the pixel pass replaying the log
// gives (each pixel's samples summed per replicate in sample order). None when the scene has no
// fixed count or the log lacks a record.
std::optional<Image> replay_radiance(const Scene& scene, const Shader& shader, const TraceLog& log,
                                     int threads);

}  // namespace countershade
