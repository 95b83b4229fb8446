#include "enhance/image_normals.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "core/parallel.h"
#include "enhance/film_lookup.h"
#include "render/shading.h"

namespace countershade {
namespace {

// One pass of the separable bilateral filter along x (step 1) or y (step = width): each object
// pixel takes the normalised sum of the object pixels within 3σ on its line, weighted by the
// spatial Gaussian and by a Gaussian of their depth difference relative to its own depth.
void bilateral_pass(const std::vector<glm::vec3>& in, std::vector<glm::vec3>& out,
                    const std::vector<float>& depth, const std::vector<char>& object, int width,
                    int height, bool along_x, double sigma, double tolerance, int threads) {
  const int radius = int(std::ceil(3 * sigma)), lines = along_x ? height : width,
            length = along_x ? width : height;
  std::vector<double> spatial(size_t(radius) + 1);
  for (int d = 0; d <= radius; ++d) spatial[size_t(d)] = std::exp(-0.5 * d * d / (sigma * sigma));
  parallel_ranges(
      size_t(lines), threads,
      [&](size_t begin, size_t end) {
        for (size_t line = begin; line < end; ++line)
          for (int i = 0; i < length; ++i) {
            const size_t p =
                along_x ? line * size_t(width) + size_t(i) : size_t(i) * size_t(width) + line;
            out[p] = in[p];
            if (!object[p]) continue;
            const double range = tolerance * depth[p];
            glm::dvec3 sum(0.0);
            for (int j = std::max(0, i - radius); j <= std::min(length - 1, i + radius); ++j) {
              const size_t q =
                  along_x ? line * size_t(width) + size_t(j) : size_t(j) * size_t(width) + line;
              if (!object[q]) continue;
              const double dz = (depth[q] - depth[p]) / range;
              sum +=
                  spatial[size_t(std::abs(j - i))] * std::exp(-0.5 * dz * dz) * glm::dvec3(in[q]);
            }
            if (glm::length(sum) > 1e-12) out[p] = glm::vec3(glm::normalize(sum));
          }
      },
      8);
}

}  // namespace

ImageNormals::ImageNormals(const View& view, double sigma1_px, int scales, double depth_tolerance,
                           int threads)
    : camera_(view.scene->camera),
      width_(view.render.gbuffer.width),
      height_(view.render.gbuffer.height),
      scales_(scales),
      sigma1_(sigma1_px),
      depth_tolerance_(depth_tolerance) {
  const GBuffer& g = view.render.gbuffer;
  object_.resize(g.normal.size());
  for (size_t i = 0; i < object_.size(); ++i)
    object_[i] = g.object[i] >= 0 && std::isfinite(view.depth[i]) && view.depth[i] > 0;
  std::vector<glm::vec3> across(g.normal.size());
  for (int k = 2; k <= scales; ++k) {
    const double sigma = sigma1_px * std::pow(kNormalScaleRatio, k - 2);
    std::vector<glm::vec3> filtered(g.normal.size());
    bilateral_pass(g.normal, across, view.depth, object_, width_, height_, true, sigma,
                   depth_tolerance, threads);
    bilateral_pass(across, filtered, view.depth, object_, width_, height_, false, sigma,
                   depth_tolerance, threads);
    normals_.push_back(std::move(filtered));
  }
}

glm::dvec3 ImageNormals::at(const glm::dvec2& film, int k, const glm::dvec3& fallback) const {
  const std::vector<glm::vec3>& normals = normals_[size_t(k - 2)];
  const glm::dvec3 sum =
      interpolate_in_mask<glm::dvec3>(film, width_, height_, object_, [&](size_t i) {
        return glm::dvec3(normals[i]);
      }).first;
  return glm::length(sum) > 1e-12 ? glm::normalize(sum) : fallback;
}

void ImageNormals::at_shading_point(const ShadingInputs& s, glm::dvec3* n) const {
  const glm::dvec2 film = camera_.film_position(s.point.position);
  n[0] = s.normal;
  for (int k = 2; k <= scales_; ++k) {
    n[k - 1] = at(film, k, s.normal);
    if (glm::dot(n[k - 1], s.normal) < 0) n[k - 1] = -n[k - 1];  // G-buffer normals face the camera
  }
}

nlohmann::json ImageNormals::describe() const {
  return {{"mode", "image"}, {"sigma_px", sigma1_}, {"depth_tolerance", depth_tolerance_}};
}

}  // namespace countershade
