#pragma once
// What a render makes and what it is asked for, shared by the passes (render/pixel_pass.h,
// render/vertex_pass.h), the trace log and the renderer that runs them (render/renderer.h): the
// G-buffer, the vertex signal, the methods' pixel request, the options and the result.

#include <cstdint>
#include <functional>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"
#include "render/hooks.h"
#include "render/ray_tracer.h"
#include "render/sample_field.h"
#include "render/scene.h"

namespace countershade {

class TraceLog;

// Per-pixel data from the ray through each pixel centre. Background pixels have object = -1,
// depth = +inf and a zero normal.
struct GBuffer {
  int width = 0, height = 0;
  std::vector<float> depth;               // linear eye depth
  std::vector<glm::vec3> normal;          // world-space shading normal, facing the camera
  std::vector<int32_t> object, triangle;  // ids, -1 for background
  std::vector<glm::vec2> barycentrics;    // (b1, b2) of the hit triangle
  std::vector<uint8_t> back;              // 1 where the camera sees the back of the triangle
  size_t index(int x, int y) const { return size_t(y) * width + x; }
};

struct SampleCounts {
  uint32_t min = 0, max = 0;
  double mean = 0;
};

// The per-vertex signal: outgoing radiance towards the camera for the front of every vertex and,
// for objects that the camera sees from behind somewhere, for the back; and the standard error of
// each value's L*.
struct VertexSignal {
  std::vector<std::vector<glm::vec3>> front, back;  // [object][vertex]; back empty where unseen
  std::vector<std::vector<float>> front_noise, back_noise;  // [object][vertex], L*
  SampleCounts samples;                                     // per shading point
  double seconds = 0;
};

// What the methods of a view ask of the pixel pass, once the vertex signal exists.
struct PixelRequest {
  struct Change {
    std::shared_ptr<const ChangePerLambda> change;
    size_t first_field = 0;  // its method's fields start here in `fields`
  };
  SampleFields fields;
  std::vector<Change> changes;  // every pixel meets the budget for each of them at ±max_abs_lambda
  double max_abs_lambda = 0;
  double share = 1.0;  // of the noise budget left to the pixels' own noise
};

struct SamplingReport {
  SampleCounts pixels;
  bool budget_met = true;  // every pixel sampled to its target
  std::string stopped_by;  // "", "max_spp", "time_limit"
  int rounds = 0;
  double seconds = 0;
};

struct RenderResult {
  Image radiance;  // linear RGB
  GBuffer gbuffer;
  VertexSignal vertices;                   // when requested
  std::vector<std::vector<float>> fields;  // [field][pixel]: mean over the pixel's samples
  // Per pixel: the display luminance (exposed, clamped to [0,1] per channel) of each surface's
  // mean radiance, weighted by the share of the pixel's samples on that surface and summed, over
  // the surfaces and the background (`luminance`) and over the surfaces alone
  // (`surface_luminance`); and the share of samples that hit a surface (render/surface_sums.h).
  std::vector<float> luminance, surface_luminance, coverage;
  std::vector<float> noise;  // per pixel: the standard error of its L*, pooled over 3×3 neighbours
  std::vector<ChangeNoise> change_noise;  // per requested change
  std::vector<uint32_t> spp;              // per pixel
  SamplingReport sampling;
  RayCounts rays;  // traced (a replayed render traces only what its log lacks)
  std::shared_ptr<const TraceLog> trace;  // with RenderOptions::record_trace, if it fit its limit
};

// What the methods need of one object's vertex signal: the L* standard error its relevant
// vertices must reach, and how far around the visible surface (in rings of the welded 1-ring
// graph) a vertex is relevant. Other shaded vertices take the first round's samples only.
struct VertexNeed {
  double noise = 0.5;
  int rings = 0;
  // How many rings the method's use of the signal reaches (its smoothing's support): a vertex
  // farther than this, and than `rings` + 1, from every triangle the camera may see cannot change
  // a pixel, and is not shaded (its value is 0). −1: every vertex is shaded.
  int support = -1;
};

struct RenderOptions {
  int threads = 0;               // 0 = all cores
  bool vertex_radiance = false;  // pass 2
  int ring_samples = 0;          // per-vertex anti-aliasing: points per incident triangle
  // Per object (default: the budget's target for every vertex seen, and one ring around them).
  std::vector<VertexNeed> vertex_needs;
  std::shared_ptr<const ShadingHook> shading_hook;  // optional (render/hooks.h)
  std::shared_ptr<const TextureHook> texture_hook;
  // Keep the tracer's answers of passes 1 and 3 (render/trace_log.h) for renders with hooks.
  bool record_trace = false;
  // Read back the answers of an earlier render of the same scene and camera instead of tracing
  // them (its log, with hooks of this render only: the image is the one tracing would give).
  std::shared_ptr<const TraceLog> replay_trace;
  uint64_t trace_byte_limit = uint64_t(1) << 30;  // a log that would outgrow it is given up
  // false: a render with a fixed sample count skips its noise estimate, leaving `noise` at 0 and
  // `change_noise` empty (renders whose display is all that is kept).
  bool estimate_noise = true;
  // true: only the radiance image is kept. A render at a fixed sample count that replays a log
  // holding every sample's shading record then evaluates the records and nothing else: its result
  // has the radiance and spp alone (render/record_replay.h).
  bool radiance_only = false;
  // false: a render with a fixed sample count traces its camera rays in the pixel pass one by one,
  // instead of a pixel's samples at a time in packets (ahead of a vertex pass, or in the pixel
  // pass): the same image, for comparisons.
  bool trace_ahead = true;
  // Called between passes 2 and 3 with what is rendered so far.
  std::function<PixelRequest(const RenderResult&)> before_pixels;
  std::function<void(double)> progress;  // called with the finished fraction, from any thread
};

// The fixed barycentric coordinates (b0, b1, b2) of sample j of k on every triangle: stratified
// over the triangle's area.
glm::dvec3 triangle_sample_barycentrics(int j, int k);

// The display luminance of linear radiance: exposed (clamped to [0,1] and lifted by the black
// level) per channel, Y of sRGB primaries. L* of a pixel or a vertex is the CIELAB lightness of it.
double display_luminance(const glm::dvec3& radiance, const Exposure& exposure);

}  // namespace countershade
