#pragma once
// The ray tracer's answers to one render, kept for renders of the same view with hooks.
//
// Hooks change how a point is shaded or textured, never which rays are traced: a render with
// hooks takes the same camera samples, hits the same points and asks the same shadow rays as the
// render without them (the shader asks a shadow ray whenever either path could use it, see
// ShadowAnswers). So such a render can read every answer back instead of tracing it, and gives the
// image it would give by tracing, bit for bit. That makes an extra λ of a method that renders
// again (shading and texture hooks) cost its shading, not its rays.

#include <cstdint>
#include <optional>
#include <vector>

#include "render/ray_tracer.h"
#include "render/renderer.h"
#include "render/shading.h"

namespace countershade {

// One camera sample's hit as the tracer reported it, and where its shadow answers start.
struct TracedHit {
  int32_t object = -1;  // -1: the ray hit nothing
  uint32_t triangle = 0;
  float b1 = 0, b2 = 0;  // the tracer's single-precision barycentrics
  uint32_t first_answer = 0;
};

class TraceLog {
 public:
  // A log that would outgrow `byte_limit` is given up (an adaptive render of a large image can take
  // tens of millions of samples); without it, renders with hooks trace their rays.
  TraceLog(size_t pixels, uint64_t byte_limit) : byte_limit_(byte_limit), pixels_(pixels) {}

  // Recording (one thread per pixel at a time, samples in order).
  void reserve(size_t pixel, uint32_t samples) { pixels_[pixel].hits.reserve(samples); }
  void record_hit(size_t pixel, uint32_t sample, const std::optional<Hit>& hit);
  std::vector<uint8_t>* answers_to_record(size_t pixel) { return &pixels_[pixel].answers; }
  // The bytes the log would hold once every pixel has `planned` samples (at the answers per
  // sample seen so far).
  uint64_t projected_bytes(uint64_t planned) const;
  uint64_t byte_limit() const { return byte_limit_; }
  // Frees what was recorded; an abandoned log records and replays nothing.
  void abandon();
  bool abandoned() const { return abandoned_; }

  // Replaying: whether sample `sample` of `pixel` was recorded; its hit and its answers.
  bool has(size_t pixel, uint32_t sample) const { return !abandoned_ && sample < pixels_[pixel].hits.size(); }
  std::optional<Hit> hit(size_t pixel, uint32_t sample) const;
  ShadowAnswers answers(size_t pixel, uint32_t sample) const;

  size_t pixel_count() const { return pixels_.size(); }
  GBuffer gbuffer;  // the render's pass 1, which hooks do not change either

 private:
  struct Pixel {
    std::vector<TracedHit> hits;
    std::vector<uint8_t> answers;  // 1: the shadow ray reached the light
  };
  uint64_t byte_limit_;
  bool abandoned_ = false;
  std::vector<Pixel> pixels_;
};

}  // namespace countershade
