#pragma once
// The ray tracer's answers to one render, kept for renders of the same view with hooks.
//
// Hooks change how a point is shaded or textured, never which of the render's rays are traced: a
// render with hooks takes the same camera samples, hits the same points and asks the same shadow
// rays as the render without them (see ShadowAnswers). So such a render can read every answer back
// instead of tracing it, and gives the image it would give by tracing, bit for bit. (A hook that
// lights the original light's dark side traces rays of its own there, per λ: render/hooks.h.) That
// makes an extra λ of a method that renders again (shading and texture hooks) cost its shading, not
// its rays.
//
// While it fits, the log also keeps every sample's shading record (render/shading.h: its albedo,
// its UV footprint and its light samples with their visibility; the point comes again from the
// hit) or, for a ray that hit nothing, the background it saw. A render with hooks then only
// evaluates each record again with its hooks: no sampling, no camera ray, no light sampling. The
// records take about 100 bytes a hit plus 64 a light sample, so they are given up first, when the
// log would outgrow half its limit; the hits and answers stay.

#include <cstdint>
#include <optional>
#include <vector>

#include "render/ray_tracer.h"
#include "render/render_types.h"
#include "render/shading.h"

namespace countershade {

// One camera sample's hit as the tracer reported it, and where its shadow answers start.
struct TracedHit {
  PackedHit hit{-1, 0, 0, 0};
  uint32_t first_answer = 0;
  uint32_t shaded =
      0;  // its shading record (a hit) or background (a miss), while the log keeps them
};

class TraceLog {
 public:
  // A log that would outgrow `byte_limit` is given up (an adaptive render of a large image can take
  // tens of millions of samples); without it, renders with hooks trace their rays.
  // `light_samples`: the shader's light samples per shading point (Shader::light_samples).
  TraceLog(size_t pixels, uint64_t byte_limit, size_t light_samples)
      : byte_limit_(byte_limit), light_samples_(light_samples), pixels_(pixels) {}

  // Recording (one thread per pixel at a time, samples in order).
  // Room for a pixel's first `samples` samples, of which about `hits` hit a surface.
  void reserve(size_t pixel, uint32_t samples, uint32_t hits);
  void record_hit(size_t pixel, uint32_t sample, const std::optional<Hit>& hit);
  std::vector<uint8_t>* answers_to_record(size_t pixel) { return &pixels_[pixel].answers; }
  // Room for the shading record of the hit just recorded (and its light samples), or the
  // background of the miss just recorded; nothing once the records are given up.
  bool keeps_shading() const { return keeps_shading_; }
  std::pair<ShadingRecord*, LightSampleRecord*> shading_to_record(size_t pixel);
  void record_background(size_t pixel, const glm::dvec3& radiance);
  // The bytes the log would hold once every pixel has `planned` samples (at the answers and
  // records per sample seen so far), with and without the shading records.
  uint64_t projected_bytes(uint64_t planned, bool with_shading) const;
  uint64_t byte_limit() const { return byte_limit_; }
  // Frees the shading records; the hits and answers stay.
  void drop_shading();
  // Frees what was recorded; an abandoned log records and replays nothing.
  void abandon();
  bool abandoned() const { return abandoned_; }

  // Replaying: whether sample `sample` of `pixel` was recorded; its hit and its answers.
  bool has(size_t pixel, uint32_t sample) const {
    return !abandoned_ && sample < pixels_[pixel].hits.size();
  }
  std::optional<Hit> hit(size_t pixel, uint32_t sample) const {
    return pixels_[pixel].hits[sample].hit.unpack();
  }
  ShadowAnswers answers(size_t pixel, uint32_t sample) const;
  // Whether the sample's shading was kept; a hit's record and light samples, or the background a
  // miss saw. (Defined here, as `hit` is: a replay calls them for every sample.)
  bool has_shading(size_t pixel, uint32_t sample) const {
    return keeps_shading_ && has(pixel, sample);
  }
  const ShadingRecord& shading(size_t pixel, uint32_t sample) const {
    return pixels_[pixel].records[pixels_[pixel].hits[sample].shaded];
  }
  const LightSampleRecord* light_samples(size_t pixel, uint32_t sample) const {
    return pixels_[pixel].lights.data() +
           size_t(pixels_[pixel].hits[sample].shaded) * light_samples_;
  }
  glm::dvec3 background(size_t pixel, uint32_t sample) const {
    return pixels_[pixel].backgrounds[pixels_[pixel].hits[sample].shaded];
  }

  size_t pixel_count() const { return pixels_.size(); }
  GBuffer gbuffer;  // the render's pass 1, which hooks do not change either

 private:
  struct Pixel {
    std::vector<TracedHit> hits;
    std::vector<uint8_t> answers;        // 1: the shadow ray reached the light
    std::vector<ShadingRecord> records;  // the hits' shading, in sample order
    std::vector<LightSampleRecord> lights;
    std::vector<glm::dvec3> backgrounds;  // the misses'
  };
  uint64_t byte_limit_;
  size_t light_samples_;
  bool abandoned_ = false;
  bool keeps_shading_ = true;
  std::vector<Pixel> pixels_;
};

}  // namespace countershade
