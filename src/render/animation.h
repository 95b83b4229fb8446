#pragma once
// Keyframed paths over time for moving stimuli (docs/scene-format.md, "Animation"): the camera
// (eye, target, field of view), lights (direction, position, intensity) and objects (a transform
// applied after their static one), each a path of keys at strictly increasing times,
// interpolated linearly or with a Catmull–Rom spline, plus a duration and a frame rate.

#include <glm/vec3.hpp>
#include <optional>
#include <string>
#include <vector>

namespace countershade {

enum class Interpolation { linear, catmull_rom };

// A path of 3-vectors (scalars use .x) over time. Before the first key and after the last it
// holds their values; at a key's time it is exactly that key's value. The Catmull–Rom spline is
// the cubic Hermite spline whose tangent at key i is (p[i+1] − p[i−1]) / (t[i+1] − t[i−1])
// (one-sided at the ends), so it is C¹ over non-uniform times.
class Track {
 public:
  // Throws std::invalid_argument unless there are ≥ 2 keys at strictly increasing times.
  Track(std::vector<double> times, std::vector<glm::dvec3> values, Interpolation mode);
  glm::dvec3 at(double time) const;
  const std::vector<double>& times() const { return times_; }

 private:
  glm::dvec3 tangent(size_t key) const;
  std::vector<double> times_;
  std::vector<glm::dvec3> values_;
  Interpolation mode_;
};

struct CameraPath {
  std::optional<Track> eye, target, fov;
};

// A light of the scene file's `lights` list, by its index there.
struct LightPath {
  size_t light = 0;         // its index in the file's list (for messages)
  bool directional = true;  // which typed list of the scene holds it
  size_t index = 0;         // its index there
  std::optional<Track> direction, position,
      intensity;  // intensity: irradiance of a directional light
};

// An object's motion: translate, rotate (degrees about x, then y, then z) and scale, composed like
// a static transform (scale, rotate, translate) and applied after the object's own transform.
struct ObjectPath {
  size_t object = 0;
  std::optional<Track> translate, rotate, scale;
};

struct Animation {
  double duration = 1;  // seconds
  double fps = 30;
  CameraPath camera;
  std::vector<LightPath> lights;
  std::vector<ObjectPath> objects;

  // Frames 0 … count − 1 at t = frame / fps, count = ⌊duration·fps⌋ (at least 1): the end is
  // excluded, so a path that returns to its start loops without a repeated frame.
  int frame_count() const;
  double time_of(int frame) const { return frame / fps; }
};

}  // namespace countershade
