#include "enhance/depth_coverage.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "core/parallel.h"
#include "enhance/view.h"
#include "render/camera.h"
#include "render/shading.h"

namespace countershade {
namespace {

constexpr int kGrid = 4;  // sub-samples per pixel side

// The means of min(ΔD_s, 0) and max(ΔD_s, 0) over the sub-samples s of pixel (x, y).
std::pair<float, float> sampled_terms(const View& view, const CameraRays& camera, int x, int y,
                                      float blurred, const std::function<float(float)>& normalise) {
  double darker = 0, lighter = 0;
  for (int j = 0; j < kGrid; ++j)
    for (int i = 0; i < kGrid; ++i) {
      const Ray ray = camera.ray(x + (i + 0.5) / kGrid, y + (j + 0.5) / kGrid);
      const auto hit = view.tracer->intersect(ray.origin, ray.direction);
      float depth = INFINITY;
      if (hit)
        depth = float(camera.eye_depth(
            surface_point(*view.scene, hit->object, hit->triangle, hit->b1, hit->b2).position));
      const float dd = blurred - normalise(depth);
      darker += std::min(dd, 0.0f);
      lighter += std::max(dd, 0.0f);
    }
  constexpr double kSamples = kGrid * kGrid;
  return {float(darker / kSamples), float(lighter / kSamples)};
}

}  // namespace

bool depth_edge_at(const View& view, int x, int y) {
  const int w = view.width(), h = view.height();
  const size_t p = size_t(y) * w + x;
  const float d = view.depth[p];
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int nx = x + dx, ny = y + dy;
      if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
      const size_t q = size_t(ny) * w + nx;
      const float e = view.depth[q];
      if (view.object_at(q) != view.object_at(p)) return true;
      if (valid_eye_depth(d) != valid_eye_depth(e)) return true;
      if (valid_eye_depth(d) && std::abs(d - e) > 0.05f * std::min(d, e)) return true;
    }
  return false;
}

void sample_outlines(const View& view, const Image& blurred,
                     const std::function<float(float)>& normalise, Image& darker, Image& lighter,
                     int threads) {
  const int w = blurred.width, h = blurred.height;
  if (!view.scene || !view.tracer || view.depth.size() != size_t(w) * h) return;
  const CameraRays camera(view.scene->camera);
  parallel_ranges(
      size_t(h), threads,
      [&](size_t begin, size_t end) {
        for (size_t y = begin; y < end; ++y)
          for (int x = 0; x < w; ++x) {
            if (!depth_edge_at(view, x, int(y))) continue;
            const size_t p = y * size_t(w) + x;
            std::tie(darker.pixels[p], lighter.pixels[p]) =
                sampled_terms(view, camera, x, int(y), blurred.pixels[p], normalise);
          }
      },
      8);
}

}  // namespace countershade
