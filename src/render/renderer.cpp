#include "render/renderer.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/parallel.h"
#include "core/random.h"
#include "render/shading.h"

namespace countershade {
namespace {

constexpr int kTile = 16;

// Latin-hypercube positions for `spp` samples in the unit pixel: stratified in x and y alike.
// A single sample sits at the pixel centre, on the G-buffer's own ray.
void pixel_samples(uint64_t seed, uint64_t pixel, int spp, std::vector<glm::dvec2>& out) {
  out.resize(size_t(spp));
  if (spp == 1) {
    out[0] = {0.5, 0.5};
    return;
  }
  SampleStream random(seed, kDomainCamera, pixel, 0);
  std::vector<int> permutation(static_cast<size_t>(spp));
  for (int i = 0; i < spp; ++i) permutation[size_t(i)] = i;
  for (int i = spp - 1; i > 0; --i)
    std::swap(permutation[size_t(i)], permutation[size_t(std::min(i, int(random.next() * (i + 1))))]);
  for (int i = 0; i < spp; ++i)
    out[size_t(i)] = {(i + random.next()) / spp, (permutation[size_t(i)] + random.next()) / spp};
}

}  // namespace

RenderResult render(const Scene& scene, const RayTracer& tracer, const RenderOptions& options) {
  const Camera& camera = scene.camera;
  const int width = camera.width, height = camera.height, spp = scene.settings.spp;
  const uint64_t seed = scene.settings.seed;
  CameraRays rays(camera);
  Shader shader(scene, tracer, options.shading_hook.get(), options.texture_hook.get());

  RenderResult result;
  result.radiance = Image(width, height, 3);
  GBuffer& g = result.gbuffer;
  g.width = width;
  g.height = height;
  size_t n = size_t(width) * height;
  g.depth.assign(n, std::numeric_limits<float>::infinity());
  g.normal.assign(n, glm::vec3(0.0f));
  g.object.assign(n, -1);
  g.triangle.assign(n, -1);
  g.barycentrics.assign(n, glm::vec2(0.0f));

  const int tiles_x = (width + kTile - 1) / kTile, tiles_y = (height + kTile - 1) / kTile;
  const size_t tile_count = size_t(tiles_x) * tiles_y;
  std::mutex counts_mutex;
  std::atomic<size_t> tiles_done{0};

  parallel_ranges(tile_count, options.threads, [&](size_t begin, size_t end) {
    RayCounts counts;
    std::vector<glm::dvec2> offsets;
    for (size_t tile = begin; tile < end; ++tile) {
      int x0 = int(tile % tiles_x) * kTile, y0 = int(tile / tiles_x) * kTile;
      for (int y = y0; y < std::min(y0 + kTile, height); ++y)
        for (int x = x0; x < std::min(x0 + kTile, width); ++x) {
          uint64_t pixel = uint64_t(y) * width + x;
          // G-buffer from the pixel-centre ray.
          Ray centre = rays.ray(x + 0.5, y + 0.5);
          ++counts.primary;
          if (auto hit = tracer.intersect(centre.origin, centre.direction)) {
            SurfacePoint sp = surface_point(scene, hit->object, hit->triangle, hit->b1, hit->b2);
            glm::dvec3 nrm = sp.shading_normal;
            if (glm::dot(sp.geometric_normal, -centre.direction) < 0) nrm = -nrm;
            g.depth[pixel] = float(rays.eye_depth(sp.position));
            g.normal[pixel] = glm::vec3(nrm);
            g.object[pixel] = int32_t(hit->object);
            g.triangle[pixel] = int32_t(hit->triangle);
            g.barycentrics[pixel] = glm::vec2(float(hit->b1), float(hit->b2));
          }
          // Supersampled radiance.
          pixel_samples(seed, pixel, spp, offsets);
          glm::dvec3 sum(0.0);
          for (int s = 0; s < spp; ++s) {
            Ray ray = rays.ray(x + offsets[size_t(s)].x, y + offsets[size_t(s)].y);
            ++counts.primary;
            auto hit = tracer.intersect(ray.origin, ray.direction);
            if (!hit) {
              sum += shader.background(ray.direction);
              continue;
            }
            SurfacePoint sp = surface_point(scene, hit->object, hit->triangle, hit->b1, hit->b2);
            SampleStream random(seed, kDomainPixel, pixel, uint64_t(s));
            sum += shader.radiance(sp, -ray.direction, true, random, counts);
          }
          for (int c = 0; c < 3; ++c) result.radiance.at(x, y, c) = float(sum[c] / spp);
        }
      if (options.progress) options.progress(double(++tiles_done) / double(tile_count));
    }
    std::lock_guard<std::mutex> lock(counts_mutex);
    result.rays += counts;
  });

  if (options.vertex_radiance)
    result.vertex_radiance = render_vertex_radiance(scene, tracer, options, &result.rays);
  return result;
}

glm::dvec3 triangle_sample_barycentrics(int j, int k) {
  // Stratified in the first coordinate, golden-ratio sequence in the second, warped uniformly
  // onto the triangle.
  double r1 = (j + 0.5) / k, r2 = std::fmod(0.5 + 0.6180339887498949 * j, 1.0);
  double s = std::sqrt(r1);
  return {1.0 - s, s * (1.0 - r2), s * r2};
}

std::vector<std::vector<glm::vec3>> render_vertex_radiance(const Scene& scene, const RayTracer& tracer,
                                                           const RenderOptions& options, RayCounts* total) {
  const int threads = options.threads, ring_samples = options.ring_samples;
  CameraRays rays(scene.camera);
  Shader shader(scene, tracer, options.shading_hook.get(), options.texture_hook.get());
  const int spp = scene.settings.vertex_samples();
  const uint64_t seed = scene.settings.seed;
  std::vector<std::vector<glm::vec3>> out(scene.objects.size());
  std::mutex counts_mutex;
  uint64_t vertex_offset = 0, triangle_offset = 0;

  for (size_t o = 0; o < scene.objects.size(); ++o) {
    const TriangleMesh& mesh = scene.objects[o].mesh;
    const size_t nv = mesh.vertex_count();
    // Incident corners per vertex, to find each vertex's distinct shading variants.
    const auto [offsets, corners] = vertex_corners(mesh);

    // Ring supersampling: the sum of k shaded points on every triangle, shared by its 3 vertices.
    std::vector<glm::dvec3> triangle_sum;
    if (ring_samples > 0) {
      triangle_sum.assign(mesh.triangle_count(), glm::dvec3(0.0));
      parallel_ranges(mesh.triangle_count(), threads, [&](size_t begin, size_t end) {
        RayCounts counts;
        for (size_t t = begin; t < end; ++t)
          for (int j = 0; j < ring_samples; ++j) {
            glm::dvec3 b = triangle_sample_barycentrics(j, ring_samples);
            SurfacePoint sp = surface_point(scene, unsigned(o), unsigned(t), b.y, b.z);
            SampleStream random(seed, kDomainTriangle, triangle_offset + t, uint64_t(j));
            triangle_sum[t] += shader.radiance(sp, rays.towards_viewer(sp.position), false, random, counts);
          }
        std::lock_guard<std::mutex> lock(counts_mutex);
        if (total) *total += counts;
      });
    }
    const int own_samples = ring_samples > 0 ? 1 : spp;

    out[o].resize(nv);
    parallel_ranges(nv, threads, [&](size_t begin, size_t end) {
      RayCounts counts;
      std::vector<std::pair<uint32_t, int>> variants;  // representative corner, count
      for (size_t v = begin; v < end; ++v) {
        variants.clear();
        for (uint32_t i = offsets[v]; i < offsets[v + 1]; ++i) {
          uint32_t corner = corners[i];
          bool merged = false;
          for (auto& [rep, count] : variants) {
            bool same_normal = mesh.corner_normals[rep] == mesh.corner_normals[corner];
            bool same_uv = !mesh.has_uvs() || mesh.corner_uvs[rep] == mesh.corner_uvs[corner];
            if (same_normal && same_uv) {
              ++count;
              merged = true;
              break;
            }
          }
          if (!merged) variants.emplace_back(corner, 1);
        }
        glm::dvec3 sum(0.0);
        int weight = 0;
        for (const auto& [corner, count] : variants) {
          unsigned triangle = corner / 3, c = corner % 3;
          SurfacePoint sp = surface_point(scene, unsigned(o), triangle, c == 1 ? 1.0 : 0.0, c == 2 ? 1.0 : 0.0);
          sp.position = mesh.positions[v];  // exactly the vertex, not a barycentric round-off
          glm::dvec3 wo = rays.towards_viewer(sp.position);
          glm::dvec3 value(0.0);
          for (int s = 0; s < own_samples; ++s) {
            SampleStream random(seed, kDomainVertex, vertex_offset + v, uint64_t(s));
            value += shader.radiance(sp, wo, false, random, counts);
          }
          sum += double(count) * value / double(own_samples);
          weight += count;
        }
        glm::dvec3 value = weight > 0 ? sum / double(weight) : glm::dvec3(0.0);
        if (ring_samples > 0) {
          // The vertex value and every point of every incident triangle, equally weighted.
          glm::dvec3 ring(0.0);
          for (uint32_t i = offsets[v]; i < offsets[v + 1]; ++i) ring += triangle_sum[corners[i] / 3];
          double points = double(ring_samples) * double(offsets[v + 1] - offsets[v]);
          value = (value + ring) / (1.0 + points);
        }
        out[o][v] = glm::vec3(value);
      }
      std::lock_guard<std::mutex> lock(counts_mutex);
      if (total) *total += counts;
    });
    vertex_offset += nv;
    triangle_offset += mesh.triangle_count();
  }
  return out;
}

}  // namespace countershade
