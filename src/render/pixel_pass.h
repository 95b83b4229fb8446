#pragma once
// The pixels of a render, sampled until each meets the noise budget.
//
// Every pixel's samples form two replicates with independent scrambles (core/sampler.h); half the
// difference of the replicates' L* estimates the standard error of the pixel's L*, and likewise
// for every change per λ the methods ask for (render/sample_field.h), so the noise of every
// stimulus L + λ·c is known. Sampling goes in rounds: every pixel starts with min_spp samples, and
// a pixel whose largest stimulus noise at ±λ_max, averaged over its neighbourhood (two 3×3
// means), still exceeds its share of the budget doubles its samples, up to max_spp. The decisions
// depend only on the samples, never on timing (unless a time limit stops the rounds), so the
// image is the same at any thread count.

#include <functional>

#include "render/render_types.h"
#include "render/shading.h"
#include "render/trace_log.h"

namespace countershade {

class CameraHits;

struct PixelPassInput {
  const Scene& scene;
  const RayTracer& tracer;
  const Shader& shader;
  const PixelRequest& request;
  int threads = 0;
  std::function<void(double)> progress;
  TraceLog* record = nullptr;        // keeps every sample's ray answers (render/trace_log.h)
  const TraceLog* replay = nullptr;  // reads back those it holds instead of tracing them
  bool estimate_noise = true;  // false: a fixed count skips the noise estimate (noise stays 0)
  const CameraHits* camera_hits =
      nullptr;  // the camera samples' hits, traced ahead (render/camera_samples.h)
  // Without hits traced ahead, a fixed count's camera rays are traced a pixel's samples at a time
  // as packets (false: one by one, for comparisons).
  bool camera_packets = false;
};

// Fills the result's radiance, fields, luminances, coverage, noise, spp and sampling report.
void pixel_pass(const PixelPassInput& input, RenderResult& result);

// Sees the samples of a render as they are shaded (observe_samples).
class SampleObserver {
 public:
  virtual ~SampleObserver() = default;
  // One sample that hit a surface: its point (with its UV footprint), its shading record and light
  // samples, which `shader` can evaluate again (e.g. with another albedo).
  virtual void surface(size_t pixel, const Shader& shader, const SurfacePoint& point,
                       const ShadingRecord& record, const LightSampleRecord* lights) = 0;
  // The pixel's `samples` samples have all been seen (from the thread that took them).
  virtual void pixel_done(size_t pixel, uint32_t samples) = 0;
};

// Takes the samples of an earlier render of this scene and camera again, `counts[p]` of pixel p
// (its RenderResult::spp), shaded without hooks, and shows each to `observer`: one thread per
// pixel at a time, a pixel's samples in order. `replay`, when given, is read back instead of
// tracing what it holds.
void observe_samples(const Scene& scene, const RayTracer& tracer,
                     const std::vector<uint32_t>& counts, const TraceLog* replay,
                     SampleObserver& observer, int threads = 0);

}  // namespace countershade
