#pragma once
// The one shading function. Pixels and mesh vertices both go through Shader::radiance, so the
// per-vertex signal of 3D unsharp masking is lit exactly like the image.

#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <optional>
#include <span>
#include <vector>

#include "core/sampler.h"
#include "render/directions.h"
#include "render/hooks.h"
#include "render/ray_tracer.h"
#include "render/scene.h"

namespace countershade {

struct SurfacePoint {
  glm::dvec3 position;
  glm::dvec3 geometric_normal;  // unit, on the counter-clockwise (front) side
  glm::dvec3 shading_normal;    // unit, interpolated corner normal
  glm::dvec2 uv{0.0};
  glm::dvec2 duv_dx{0.0},
      duv_dy{0.0};  // UV change per pixel along the film's x and y (0: no footprint)
  unsigned object = 0, triangle = 0;
  double b1 = 0, b2 = 0;  // barycentrics of corners 1 and 2
};

// The point at barycentrics (b1, b2) of a triangle, with interpolated normal and UV.
SurfacePoint surface_point(const Scene& scene, unsigned object, unsigned triangle, double b1,
                           double b2);

// Where the shadow rays of a point start: the point lifted onto the smooth surface its corner
// normals describe (Hanika 2021), wherever it lies below a corner's tangent plane. From the flat
// facet itself, a ray towards a light that the smooth shading normal faces but the facet does not
// would hit the neighbouring facets, and the terminator would show the mesh's facets as steps.
glm::dvec3 shadow_origin(const Scene& scene, const SurfacePoint& p, bool back);

// One sample's shadow-ray answers, in the order the shader asks for them: appended while a render
// records its rays, read back while a render with hooks replays them (render/trace_log.h). Hooks
// never change which light samples face the surface, so both renders ask the same rays in the
// same order.
struct ShadowAnswers {
  std::vector<uint8_t>* record = nullptr;
  const uint8_t* replay = nullptr;
  const uint8_t* replay_end = nullptr;
};

// One light sample as the shader drew it, enough to reflect it again with other hooks: the
// direction towards the light, its radiance and the divisor (its pdf, or r²), and whether it
// arrives (it faces the shading normal and its shadow ray, where one was asked, reached the light).
struct LightSampleRecord {
  glm::dvec3 wi{0.0}, radiance{0.0};
  double divisor = 1.0;
  bool arrives = false;
};

// What one shading point drew besides its light samples and its surface point (which the ray
// log's hit gives again): the UV footprint, the direction towards the viewer and the side it
// sees, the albedo and the share of ambient occlusion rays that escaped. Shader::evaluate turns
// it, the point and its light samples into radiance; a render with other hooks can evaluate it
// again instead of drawing it (render/trace_log.h).
struct ShadingRecord {
  glm::dvec2 duv_dx{0.0}, duv_dy{0.0};
  glm::dvec3 wo{0.0}, albedo{0.0};
  double ambient_open = 1.0;
  bool back = false;  // shaded as the back face (two-sided, seen from behind)
  // The recorded hit's point as gathered: surface_point() with the footprint.
  SurfacePoint restore(SurfacePoint p) const {
    p.duv_dx = duv_dx;
    p.duv_dy = duv_dy;
    return p;
  }
  // The point's normals on the viewed side.
  glm::dvec3 shading_normal(const SurfacePoint& p) const {
    return back ? -p.shading_normal : p.shading_normal;
  }
  glm::dvec3 geometric_normal(const SurfacePoint& p) const {
    return back ? -p.geometric_normal : p.geometric_normal;
  }
};

// One kept record to evaluate again (Shader::replay_many).
struct ReplayInput {
  const SurfacePoint* point;  // the recorded hit's surface_point() with the record's footprint
  const ShadingRecord* record;
  const LightSampleRecord* lights;
};

class Shader {
 public:
  // Hooks may be null (the plain path).
  Shader(const Scene& scene, const RayTracer& tracer, const ShadingHook* shading_hook = nullptr,
         const TextureHook* texture_hook = nullptr)
      : scene_(scene),
        tracer_(tracer),
        shading_hook_(shading_hook),
        texture_hook_(texture_hook),
        light_samples_(count_light_samples(scene)),
        dark_side_rays_(dark_side_rays(scene)),
        light_frames_(light_frames(scene)) {}

  // Outgoing radiance from `point` towards unit direction `wo`. With `two_sided`, a point seen
  // from behind its front face is shaded as the back face (open meshes, planes from below).
  // `answers` (optional) records the shadow rays' answers or replays them instead of tracing.
  glm::dvec3 radiance(const SurfacePoint& point, const glm::dvec3& wo, bool two_sided,
                      Sampler& random, RayCounts& counts, ShadowAnswers* answers = nullptr) const;

  // Shading in two steps, which radiance() chains: gather draws the light samples (tracing or
  // replaying their shadow rays) into `lights` (light_samples() entries); evaluate reflects them
  // with this shader's hooks. `replay` evaluates a record gathered by another render of the same
  // scene (its texture lookups again if this shader has a texture hook).
  size_t light_samples() const { return light_samples_; }
  void gather(const SurfacePoint& point, const glm::dvec3& wo, bool two_sided, Sampler& random,
              RayCounts& counts, ShadowAnswers* answers, ShadingRecord& record,
              LightSampleRecord* lights) const;
  glm::dvec3 evaluate(const SurfacePoint& point, const ShadingRecord& record,
                      const LightSampleRecord* lights, const glm::dvec3& albedo) const;
  // radiance() of several points (two-sided, their shadow rays neither recorded nor replayed),
  // radiance[k] for points[k]: the same values, their shadow rays traced together in wider
  // packets than one point's.
  struct PointToShade {
    const SurfacePoint* point;
    glm::dvec3 wo;
    Sampler* random;
  };
  void radiance_many(std::span<const PointToShade> points, RayCounts& counts,
                     glm::dvec3* radiance) const;
  // `point`: the recorded hit's surface_point() with the record's footprint
  // (ShadingRecord::restore).
  glm::dvec3 replay(const SurfacePoint& point, const ShadingRecord& record,
                    const LightSampleRecord* lights) const {
    return evaluate(point, record, lights, texture_hook_ ? albedo(point) : record.albedo);
  }
  // replay() of many records, radiance[k] for records[k]: the shading hook reflects all their
  // light samples in one ShadingHook::reflect_many call. The same bits as replay() one by one.
  void replay_many(std::span<const ReplayInput> records, glm::dvec3* radiance) const;

  // What a camera ray that hits nothing sees.
  glm::dvec3 background(const glm::dvec3& direction) const;

  glm::dvec3 albedo(const SurfacePoint& point) const;
  // Whether `object`'s albedo may come from a texture (its material's, or the texture hook's), so
  // that its lookups need a footprint.
  bool textured(unsigned object) const {
    return scene_.objects[object].mesh.has_uvs() &&
           (texture_hook_ || scene_.objects[object].material.texture);
  }

 private:
  struct Context;      // one shading point being gathered
  struct ShadowQueue;  // its shadow rays, answered together
  static size_t count_light_samples(const Scene& scene);
  // The most shadow rays one point asks.
  size_t most_shadow_rays() const;
  // gather() in two halves around the answers: draw_samples fills the record and draws the light
  // samples into `lights`, asking their shadow rays in `queue` (true: it asked ambient occlusion
  // rays); finish_point, once the queue is answered, looks up the sky's radiance and the ambient
  // share of its rays [first, end).
  bool draw_samples(const SurfacePoint& point, const glm::dvec3& wo, bool two_sided,
                    Sampler& random, ShadowAnswers* answers, ShadowQueue& queue,
                    ShadingRecord& record, LightSampleRecord* lights) const;
  void finish_point(const ShadowQueue& queue, size_t first, size_t end, bool ambient,
                    ShadingRecord& record, LightSampleRecord* lights) const;
  // Each light type draws its samples into c.lights, in the order evaluate reads them, and asks
  // their shadow rays in c.queue.
  void directional(Context& c, Sampler& random) const;
  void point_lights(Context& c, Sampler& random) const;
  void environment(Context& c, Sampler& random) const;
  void environment_sample(Context& c, const Material& material,
                          const std::optional<glm::dvec3>& drawn, int from_lobe) const;
  void environment_from_map(Context& c, Sampler& random) const;
  // The sky's radiance of the environment's cosine-drawn samples that arrive (of a point's
  // `lights`, once its shadow rays are answered).
  void sky_radiance(LightSampleRecord* lights) const;
  static double mixture_pdf(const Context& c, const Material& material, const glm::dvec3& wi,
                            int samples, int from_lobe);
  // The ambient occlusion rays asked in c.queue (none: false, no ambient occlusion), and the share
  // of a point's rays [first, end) that escaped once answered.
  bool ambient_rays(Context& c, Sampler& random) const;
  double ambient_open(const ShadowQueue& q, size_t first, size_t end) const;
  // One light sample from `wi` with `radiance` divided by `divisor` (its pdf, or 1/r²'s r²),
  // `distance` away (0: no shadow ray). Whether it arrives is known once the queue is answered.
  LightSampleRecord& draw(Context& c, const glm::dvec3& wi, const glm::dvec3& radiance,
                          double divisor, double distance) const;
  // The shadow ray from the point towards `wi`, ending `distance` away, into `ray`.
  void shadow_ray(const Context& c, const glm::dvec3& wi, double distance, ShadowRay& ray) const;
  // Answers the queue's rays, traced or replayed (and recorded where a render records them), in
  // the order they were asked.
  void answer_shadows(ShadowQueue& queue, ShadowAnswers* answers, RayCounts& counts) const;
  // One shadow ray traced at once (the dark side's, neither recorded nor replayed).
  bool visible(const Context& c, const glm::dvec3& wi, double distance, RayCounts& counts) const;
  ShadingInputs inputs(const SurfacePoint& point, const ShadingRecord& r,
                       const glm::dvec3& albedo) const {
    return {point, scene_.objects[point.object].material, r.shading_normal(point), r.wo, albedo};
  }
  // evaluate() for given inputs. `hooked` (optional): the hook's reflections of the arriving light
  // samples in order, read and advanced instead of asking the hook one sample at a time.
  // `lit` (optional): sample_lit of each of the point's light samples, read instead of deciding it.
  glm::dvec3 evaluate_inputs(const ShadingInputs& s, const ShadingRecord& r,
                             const LightSampleRecord* lights, const glm::dvec3*& hooked,
                             const uint8_t* lit = nullptr) const;
  // The reflection of one arriving light sample (through the shading hook if there is one; its
  // value taken from `hooked` when that is not null).
  glm::dvec3 reflect(const ShadingInputs& s, const LightSampleRecord& light,
                     const glm::dvec3*& hooked) const;
  // The original light's dark side (ShadingHook::dark_side_direction). How a light sample's dark
  // side could be lit: the shadow ray it would need, per sample index in drawing order.
  enum class DarkSideRay : uint8_t { never, none, to_infinity, to_point };
  static std::vector<DarkSideRay> dark_side_rays(const Scene& scene);
  static std::vector<TangentFrame> light_frames(const Scene& scene);
  // What this shader does with light sample k if it did not arrive: leave it dark (it faces the
  // normal and is shadowed, or the hook does not shade the dark side), reflect it through the hook
  // as it is (its light casts no shadows), or trace the hook's direction first.
  enum class DarkSide { dark, unshadowed, traced };
  DarkSide dark_side(const ShadingInputs& s, const LightSampleRecord& light, size_t k) const;
  // Whether a dark-side sample that needs a ray is lit: the hook's direction `towards` faces the
  // normal and its shadow ray is open.
  bool dark_side_open(const ShadingInputs& s, const ShadingRecord& r,
                      const LightSampleRecord& light, size_t k,
                      const std::optional<glm::dvec3>& towards) const;
  // Whether light sample k of a point is reflected: it arrives, or it lies on a dark side the hook
  // lights (with the hook's direction open where its light casts shadows).
  bool sample_lit(const ShadingInputs& s, const ShadingRecord& r, const LightSampleRecord& light,
                  size_t k) const;
  // sample_lit of every light sample of `records`, record by record (records.size() × light
  // samples), the dark side's directions asked of the hook for all of them at once.
  void lit_samples(std::span<const ReplayInput> records, std::span<const ShadingInputs> points,
                   std::vector<uint8_t>& lit) const;

  const Scene& scene_;
  const RayTracer& tracer_;
  const ShadingHook* shading_hook_;
  const TextureHook* texture_hook_;
  size_t light_samples_;
  std::vector<DarkSideRay> dark_side_rays_;
  std::vector<TangentFrame> light_frames_;  // one per directional light, around its direction
};

}  // namespace countershade
