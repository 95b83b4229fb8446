#pragma once
// Hooks through which an enhancement method reaches into rendering (docs/architecture.md).
// Both are optional: a render without hooks takes the plain path and pays nothing for them.
//
// - A shading hook changes how one light sample is reflected: it may shade with another light
//   (or guide) direction per shading component, or scale or replace the result. Where the point
//   faces the original light, visibility (shadow rays, environment occlusion) is that of the
//   original direction. On the original light's dark side (n·wi ≤ 0, its attached shadow) a hook
//   may shade too (dark_side_direction): the sample then arrives if the direction the hook shades
//   with is open. Optionally the hook's change fades out within a band of the original light's
//   terminator (terminator_band, off by default), and the dark side then stays dark.
// - A texture hook replaces the texture a material samples (e.g. a filtered mip pyramid).

#include <cstddef>
#include <glm/vec3.hpp>
#include <memory>
#include <optional>
#include <span>

#include "render/scene.h"

namespace countershade {

struct SurfacePoint;

// What the shader knows at one shading point, for the viewed side of the surface.
struct ShadingInputs {
  const SurfacePoint& point;
  const Material& material;
  glm::dvec3 normal;  // shading normal, on the side the viewer sees
  glm::dvec3 wo;      // unit direction towards the viewer
  glm::dvec3 albedo;  // diffuse reflectance at the point (texture or material)
};

// The material's BRDF for light from `wi` (diffuse plus specular), and its specular part.
glm::dvec3 brdf(const ShadingInputs& s, const glm::dvec3& wi);
glm::dvec3 specular_brdf(const ShadingInputs& s, const glm::dvec3& wi);

// The plain reflection of one light sample: BRDF(wi, wo)·incident·max(0, n·wi), where
// `incident` is the sample's radiance already divided by its probability density.
glm::dvec3 reflect_plain(const ShadingInputs& s, const glm::dvec3& wi, const glm::dvec3& incident);
// The diffuse and specular parts of that reflection separately (they add up to reflect_plain).
glm::dvec3 reflect_diffuse(const ShadingInputs& s, const glm::dvec3& wi,
                           const glm::dvec3& incident);
glm::dvec3 reflect_specular(const ShadingInputs& s, const glm::dvec3& wi,
                            const glm::dvec3& incident);

// How much of a hook's change a light sample keeps, by its cosine with the shading normal, when the
// hook fades out over a band of the original terminator: smoothstep from 0 at the terminator to 1
// at cos = band. A band of 0 keeps the whole change wherever the light faces the normal.
double terminator_fade(double cos_i, double band);

// One light sample for ShadingHook::reflect_many.
struct HookSample {
  const ShadingInputs* inputs;
  glm::dvec3 wi, incident;
};

class ShadingHook {
 public:
  virtual ~ShadingHook() = default;
  // The radiance reflected towards s.wo from one visible light sample from direction `wi`.
  virtual glm::dvec3 reflect(const ShadingInputs& s, const glm::dvec3& wi,
                             const glm::dvec3& incident) const = 0;
  // reflect() for many light samples at once (a replay asks for every sample of a block of pixels
  // together), so that a hook may vectorise its work. Each out[k] must equal reflect() of
  // samples[k] bit for bit: the same stimulus comes out of a render and of a replay. It runs
  // inside the replay's parallel loop, between uses of per-thread buffers: like reflect(), it
  // must not start parallel work of its own (a waiting thread could take another block).
  virtual void reflect_many(std::span<const HookSample> samples, glm::dvec3* out) const {
    for (size_t k = 0; k < samples.size(); ++k)
      out[k] = reflect(*samples[k].inputs, samples[k].wi, samples[k].incident);
  }
  // A hook that shades the original light's dark side returns, for a light sample from behind the
  // shading normal of a light that casts shadows, the direction it shades that sample with: the
  // sample arrives (and reflect() is asked for it) when that direction faces the normal and its
  // shadow ray is open. None: that sample stays dark, as in the plain render.
  virtual std::optional<glm::dvec3> dark_side_direction(const ShadingInputs&,
                                                        const glm::dvec3&) const {
    return std::nullopt;
  }
  // Whether it shades the dark side at all. A light that casts no shadows needs no direction:
  // such a hook's reflect() is asked for its dark-side samples directly (with the others, through
  // reflect_many), and must itself give nothing where its direction is behind the normal.
  virtual bool shades_dark_side() const { return false; }
  // dark_side_direction() of many samples at once (a replay asks for all its rays' directions
  // together), so that a hook may vectorise it; out[k] must equal dark_side_direction(samples[k])
  // bit for bit.
  virtual void dark_side_directions(std::span<const HookSample> samples,
                                    std::optional<glm::dvec3>* out) const {
    for (size_t k = 0; k < samples.size(); ++k)
      out[k] = dark_side_direction(*samples[k].inputs, samples[k].wi);
  }
  // The cosine band over which the change fades out towards the original terminator (0: none).
  // With a band the dark side stays dark whatever dark_side_direction says.
  virtual double terminator_band() const { return 0; }
};

class TextureHook {
 public:
  virtual ~TextureHook() = default;
  // The texture object `object` samples instead of its material's own (nullptr: keep it).
  virtual const Texture* texture(unsigned object, const Material& material) const = 0;
};

}  // namespace countershade
