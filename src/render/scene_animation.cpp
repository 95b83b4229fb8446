#include "render/scene_animation.h"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vector_relational.hpp>
#include <stdexcept>

namespace countershade {
namespace {

// {"times": [...], "values": [...], "interpolation": "linear" | "catmull-rom"}; values are
// numbers (`scalar`) or arrays of three numbers.
Track read_track(const JsonObject& o, bool scalar, double duration) {
  const std::vector<double> times = o.numbers("times");
  const nlohmann::json& raw = o.raw("values");
  if (!raw.is_array() || raw.size() != times.size())
    o.fail("values",
           "expected an array with one value per time (" + std::to_string(times.size()) + ")");
  std::vector<glm::dvec3> values;
  for (const auto& v : raw) {
    if (scalar && v.is_number())
      values.emplace_back(v.get<double>(), 0.0, 0.0);
    else if (!scalar && v.is_array() && v.size() == 3 && v[0].is_number() && v[1].is_number() &&
             v[2].is_number())
      values.emplace_back(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
    else
      o.fail("values", scalar ? "expected numbers" : "expected arrays of 3 numbers");
    if (!std::isfinite(values.back().x) || !std::isfinite(values.back().y) ||
        !std::isfinite(values.back().z))
      o.fail("values", "must be finite");
  }
  for (double t : times)
    if (!(t >= 0 && t <= duration))
      o.fail("times", "must lie in [0, duration] = [0, " + std::to_string(duration) + "]");
  const Interpolation mode =
      o.choice("interpolation", "linear", {"linear", "catmull-rom"}) == "linear"
          ? Interpolation::linear
          : Interpolation::catmull_rom;
  o.finish();
  try {
    return Track(times, std::move(values), mode);
  } catch (const std::invalid_argument& e) {
    o.fail("times", e.what());
  }
}

std::optional<Track> optional_track(const JsonObject& o, const std::string& key, bool scalar,
                                    double duration) {
  if (!o.has(key)) return std::nullopt;
  return read_track(o.object(key), scalar, duration);
}

LightPath read_light_path(const JsonObject& o, const std::vector<LightRef>& lights,
                          double duration) {
  LightPath p;
  p.light = size_t(o.integer_in("light", 0, 0, (long long)(lights.size()) - 1));
  const LightRef::Kind kind = lights[p.light].kind;
  if (kind == LightRef::Kind::other) o.fail("light", "only directional and point lights move");
  p.directional = kind == LightRef::Kind::directional;
  p.index = lights[p.light].index;
  if (o.has("direction") && kind != LightRef::Kind::directional)
    o.fail("direction", "applies to a directional light only");
  if (o.has("position") && kind != LightRef::Kind::point)
    o.fail("position", "applies to a point light only");
  p.direction = optional_track(o, "direction", false, duration);
  p.position = optional_track(o, "position", false, duration);
  p.intensity = optional_track(o, "intensity", false, duration);
  o.finish();
  if (p.direction)
    for (double t : p.direction->times())
      if (glm::length(p.direction->at(t)) < 1e-9)
        o.fail("direction", "a key's direction has no length");
  if (p.intensity)
    for (double t : p.intensity->times())
      if (glm::any(glm::lessThan(p.intensity->at(t), glm::dvec3(0.0))))
        o.fail("intensity", "must not be negative");
  return p;
}

ObjectPath read_object_path(const JsonObject& o, const Scene& scene, double duration) {
  ObjectPath p;
  const std::string name = o.string("name");
  const auto found = std::find_if(scene.objects.begin(), scene.objects.end(),
                                  [&](const Object& x) { return x.name == name; });
  if (found == scene.objects.end())
    o.fail("name", "no object of the scene is called '" + name + "'");
  p.object = size_t(found - scene.objects.begin());
  p.translate = optional_track(o, "translate", false, duration);
  p.rotate = optional_track(o, "rotate", false, duration);
  p.scale = optional_track(o, "scale", false, duration);
  o.finish();
  return p;
}

glm::dmat4 motion(const ObjectPath& p, double t) {
  const glm::dvec3 translate = p.translate ? p.translate->at(t) : glm::dvec3(0.0);
  const glm::dvec3 rotate = p.rotate ? p.rotate->at(t) : glm::dvec3(0.0);
  const glm::dvec3 scale = p.scale ? p.scale->at(t) : glm::dvec3(1.0);
  glm::dmat4 m = glm::translate(glm::dmat4(1.0), translate);
  m = glm::rotate(m, glm::radians(rotate.z), glm::dvec3(0, 0, 1));
  m = glm::rotate(m, glm::radians(rotate.y), glm::dvec3(0, 1, 0));
  m = glm::rotate(m, glm::radians(rotate.x), glm::dvec3(1, 0, 0));
  return glm::scale(m, scale);
}

void move_camera(const CameraPath& path, double t, Camera& camera) {
  if (path.eye) camera.eye = path.eye->at(t);
  if (path.target) camera.target = path.target->at(t);
  if (path.fov)
    camera.vertical_fov_deg = std::clamp(path.fov->at(t).x, 1e-3, 179.0);  // a spline may overshoot
}

void move_light(const LightPath& path, double t, Scene& scene) {
  if (path.directional) {
    DirectionalLight& l = scene.directional_lights[path.index];
    if (path.direction) {
      const glm::dvec3 d = path.direction->at(t);
      if (glm::length(d) > 1e-9) l.direction = glm::normalize(d);  // opposite keys pass through 0
    }
    if (path.intensity) l.irradiance = glm::max(path.intensity->at(t), glm::dvec3(0.0));
  } else {
    PointLight& l = scene.point_lights[path.index];
    if (path.position) l.position = path.position->at(t);
    if (path.intensity) l.intensity = glm::max(path.intensity->at(t), glm::dvec3(0.0));
  }
}

}  // namespace

glm::dvec3 carry_point(const Scene& base, size_t object, double from, double to,
                       const glm::dvec3& point) {
  if (!base.animation) return point;
  for (const ObjectPath& o : base.animation->objects)
    if (o.object == object)
      return glm::dvec3(motion(o, to) * glm::inverse(motion(o, from)) * glm::dvec4(point, 1.0));
  return point;
}

Scene scene_at(const Scene& base, double time) {
  Scene scene = base;
  if (!base.animation) return scene;
  const Animation& a = *base.animation;
  move_camera(a.camera, time, scene.camera);
  for (const LightPath& l : a.lights) move_light(l, time, scene);
  for (const ObjectPath& o : a.objects) {
    Object& object = scene.objects[o.object];
    transform_mesh(object.mesh, motion(o, time));
    measure_edges(object.surface,
                  object.mesh.positions);  // a scene without graphs has none to measure
  }
  return scene;
}

Animation read_animation(const JsonObject& o, const Scene& scene,
                         const std::vector<LightRef>& lights) {
  Animation a;
  a.duration = o.number_in("duration", 1.0, 1e-3, 3600.0);
  a.fps = o.number_in("fps", 30.0, 1.0, 240.0);
  if (o.has("camera")) {
    const JsonObject c = o.object("camera");
    a.camera.eye = optional_track(c, "eye", false, a.duration);
    a.camera.target = optional_track(c, "target", false, a.duration);
    a.camera.fov = optional_track(c, "fov", true, a.duration);
    c.finish();
  }
  if (o.has("lights"))
    for (const auto& l : o.objects("lights"))
      a.lights.push_back(read_light_path(l, lights, a.duration));
  if (o.has("objects"))
    for (const auto& x : o.objects("objects"))
      a.objects.push_back(read_object_path(x, scene, a.duration));
  o.finish();
  return a;
}

}  // namespace countershade
