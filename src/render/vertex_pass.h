#pragma once
// The outgoing radiance towards the camera at every mesh vertex (the per-vertex signal of 3D
// unsharp masking), shaded by the same function as the pixels.
//
// A vertex's value is the mean over its shading points: the vertex itself (once per distinct
// corner, where a crease or a UV seam splits it, weighted by how many corners share each) and,
// with k ring samples, k fixed points on every incident triangle, which all three of the
// triangle's vertices share. The fixed points are the same every frame.
//
// The signal is shaded for the side of the surface the pixels show: the front of every vertex,
// and the back as well for objects that the camera sees from behind somewhere.
//
// Only what can reach a pixel is shaded: with a support (VertexNeed::support), the vertices within
// it of a triangle that some camera sample hits (known with a fixed count, render/camera_samples.h)
// or may hit (under a budget: the view's frustum, tested exactly per triangle), and their incident
// triangles' points. The rest keep the value 0, which no pixel reads.
//
// Like the pixels, every point's samples form two replicates. With a noise budget, sampling goes
// in rounds: a relevant vertex (near the visible surface) whose L* error (pooled over its 1-ring)
// exceeds its object's target doubles the samples of its own points and of its triangles'
// points. A fixed count c takes one round: c for every vertex without ring points, and with them
// c/2 (at least 1) for every point, of which a vertex averages about 6k + 1. A point with one
// sample puts it in the first or the second replicate by turns, so that a vertex's points fill
// both.

#include <functional>
#include <vector>

#include "render/camera_samples.h"
#include "render/render_types.h"
#include "render/shading.h"

namespace countershade {

struct VertexPassInput {
  const Scene& scene;
  const RayTracer& tracer;
  const Shader& shader;
  const GBuffer& gbuffer;  // which triangles the pixel centres see, and from which side
  int ring_samples = 0;
  std::vector<bool> back;         // per object: also shade the back
  std::vector<VertexNeed> needs;  // per object
  int threads = 0;
  const CameraHits* camera_hits =
      nullptr;  // with a fixed count: which triangles the camera samples hit
};

VertexSignal vertex_pass(const VertexPassInput& input, RayCounts* rays = nullptr);

}  // namespace countershade
