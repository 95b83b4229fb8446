#pragma once
// The animation block of a scene file and the scene at a moment of it (docs/scene-format.md,
// "Animation").

#include <vector>

#include "core/json_reader.h"
#include "render/animation.h"
#include "render/scene.h"

namespace countershade {

// Where a light of the scene file's `lights` list went: which typed list, and its index there.
struct LightRef {
  enum class Kind { directional, point, other } kind = Kind::other;
  size_t index = 0;
};

// Reads `animation` against the scene it animates (object names, light indices and types).
// InputError with the key path for anything wrong: unknown keys, paths with fewer than two keys
// or times that do not increase, times outside [0, duration], a key a light's type lacks.
Animation read_animation(const JsonObject& o, const Scene& scene,
                         const std::vector<LightRef>& lights);

// Where a point of object `object` at time `from` is at time `to` (its path's motion between
// them; the point itself for an object without a path).
glm::dvec3 carry_point(const Scene& base, size_t object, double from, double to,
                       const glm::dvec3& point);

// The scene at `time` seconds: camera, lights and objects moved along their paths (a copy of
// `base`; without an animation, `base` itself).
Scene scene_at(const Scene& base, double time);

}  // namespace countershade
