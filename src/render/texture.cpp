#include "render/texture.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <stdexcept>
#include <string>

#include "core/color.h"

namespace countershade {
namespace {

// The overlap of finer texels with coarser texel `i` along one axis: the finer range
// [i·ratio, (i+1)·ratio) split into whole texels with their weights (summing to 1).
struct Span {
  int first = 0, count = 0;
  double weight[3] = {0, 0, 0};  // a ratio ≤ 2 (⌊w/2⌋ of w ≥ 2) covers at most three texels
};

Span span(int i, int finer, int coarser) {
  Span s;
  if (coarser == finer) {  // a side of 1 stays 1
    s.first = i;
    s.count = 1;
    s.weight[0] = 1;
    return s;
  }
  const double ratio = double(finer) / double(coarser), begin = i * ratio, end = (i + 1) * ratio;
  s.first = int(std::floor(begin));
  for (int x = s.first; x < end && s.count < 3; ++x) {
    const double overlap = std::min(end, double(x + 1)) - std::max(begin, double(x));
    s.weight[s.count++] = overlap / ratio;
  }
  return s;
}

}  // namespace

TextureLevel level_from_image(const Image& image, bool srgb_encoded) {
  TextureLevel level{image.width, image.height,
                     std::vector<glm::vec3>(size_t(image.width) * size_t(image.height))};
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      glm::vec3 c;
      for (int k = 0; k < 3; ++k) {
        const float v = image.at(x, y, std::min(k, image.channels - 1));
        c[k] = srgb_encoded ? float(srgb_decode(v)) : v;
      }
      level.texels[size_t(y) * size_t(image.width) + size_t(x)] = c;
    }
  return level;
}

Image image_from_level(const TextureLevel& level) {
  Image image(level.width, level.height, 3, Image::Uninitialized{});
  for (size_t i = 0; i < level.texels.size(); ++i)
    for (int k = 0; k < 3; ++k) image.pixels[3 * i + size_t(k)] = level.texels[i][k];
  return image;
}

namespace {

// The four texels of a bilinear lookup at `level` (as TextureLevel::bilinear reads them), each
// with `weight` times its bilinear weight.
void bilinear_taps(const TextureLevel& t, uint32_t level, const glm::dvec2& uv, double weight,
                   std::vector<TextureTap>& out) {
  const double fx = (uv.x - std::floor(uv.x)) * t.width - 0.5;
  const double fy = (1.0 - (uv.y - std::floor(uv.y))) * t.height - 0.5;
  const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
  const double tx = fx - x0, ty = fy - y0;
  auto tap = [&](int x, int y, double w) {
    x = ((x % t.width) + t.width) % t.width;
    y = ((y % t.height) + t.height) % t.height;
    out.push_back({level, uint32_t(y) * uint32_t(t.width) + uint32_t(x), weight * w});
  };
  tap(x0, y0, (1 - ty) * (1 - tx));
  tap(x0 + 1, y0, (1 - ty) * tx);
  tap(x0, y0 + 1, ty * (1 - tx));
  tap(x0 + 1, y0 + 1, ty * tx);
}

}  // namespace

glm::dvec3 TextureLevel::bilinear(const glm::dvec2& uv) const {
  const double fx = (uv.x - std::floor(uv.x)) * width - 0.5;
  const double fy = (1.0 - (uv.y - std::floor(uv.y))) * height - 0.5;
  const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
  const double tx = fx - x0, ty = fy - y0;
  auto texel = [&](int x, int y) {
    x = ((x % width) + width) % width;
    y = ((y % height) + height) % height;
    return glm::dvec3(at(x, y));
  };
  return (1 - ty) * ((1 - tx) * texel(x0, y0) + tx * texel(x0 + 1, y0)) +
         ty * ((1 - tx) * texel(x0, y0 + 1) + tx * texel(x0 + 1, y0 + 1));
}

TextureLevel downsample(const TextureLevel& finer) {
  TextureLevel out;
  out.width = std::max(1, finer.width / 2);
  out.height = std::max(1, finer.height / 2);
  out.texels.resize(size_t(out.width) * size_t(out.height));
  std::vector<Span> columns(size_t(out.width));
  for (int x = 0; x < out.width; ++x) columns[size_t(x)] = span(x, finer.width, out.width);
  for (int y = 0; y < out.height; ++y) {
    const Span sy = span(y, finer.height, out.height);
    for (int x = 0; x < out.width; ++x) {
      const Span& sx = columns[size_t(x)];
      glm::dvec3 sum(0.0);
      for (int j = 0; j < sy.count; ++j)
        for (int i = 0; i < sx.count; ++i)
          sum += (sy.weight[j] * sx.weight[i]) * glm::dvec3(finer.at(sx.first + i, sy.first + j));
      out.texels[size_t(y) * size_t(out.width) + size_t(x)] = glm::vec3(sum);
    }
  }
  return out;
}

Texture::Texture(TextureLevel base) {
  levels_.clear();
  levels_.push_back(std::move(base));
  while (levels_.back().width > 1 || levels_.back().height > 1)
    levels_.push_back(downsample(levels_.back()));
}

Texture Texture::from_levels(std::vector<TextureLevel> levels) {
  if (levels.empty()) throw std::logic_error("a texture pyramid needs at least one level");
  for (size_t k = 1; k < levels.size(); ++k)
    if (levels[k].width != std::max(1, levels[k - 1].width / 2) ||
        levels[k].height != std::max(1, levels[k - 1].height / 2))
      throw std::logic_error("texture pyramid level " + std::to_string(k) + " has the wrong size");
  Texture t;
  t.levels_ = std::move(levels);
  return t;
}

Texture::Footprint Texture::footprint(const glm::dvec2& duv_dx, const glm::dvec2& duv_dy) const {
  const glm::dvec2 size(width(), height());
  const double x = glm::length(duv_dx * size), y = glm::length(duv_dy * size);
  const double longer = std::max(x, y), shorter = std::min(x, y);
  Footprint f;
  f.axis = x >= y ? duv_dx : duv_dy;
  if (!(longer > 1.0)) return f;  // magnified, or no footprint (also NaN): one probe at level 0
  const double ratio = shorter > 0 ? std::round(longer / shorter) : double(kMaxAnisotropy);
  f.probes = int(std::clamp(ratio, 1.0, double(kMaxAnisotropy)));
  // Each probe covers the longer side's share, but never less than the shorter side.
  const double width = std::max(shorter, longer / f.probes);
  if (width > 1.0) f.level = std::min(std::log2(width), double(levels_.size() - 1));
  return f;
}

int Texture::probes_of(const glm::dvec2& duv_dx, const glm::dvec2& duv_dy) const {
  return footprint(duv_dx, duv_dy).probes;
}

double Texture::level_of(const glm::dvec2& duv_dx, const glm::dvec2& duv_dy) const {
  return footprint(duv_dx, duv_dy).level;
}

glm::dvec3 Texture::trilinear(const glm::dvec2& uv, double level) const {
  if (level <= 0.0) return sample(uv);  // bit for bit the lookup without a pyramid
  const size_t fine = size_t(level);
  if (fine + 1 >= levels_.size()) return levels_.back().bilinear(uv);
  const double t = level - double(fine);
  return (1.0 - t) * levels_[fine].bilinear(uv) + t * levels_[fine + 1].bilinear(uv);
}

void Texture::trilinear_taps(const glm::dvec2& uv, double level, double weight,
                             std::vector<TextureTap>& out) const {
  if (level <= 0.0) return bilinear_taps(levels_.front(), 0, uv, weight, out);
  const size_t fine = size_t(level);
  if (fine + 1 >= levels_.size())
    return bilinear_taps(levels_.back(), uint32_t(levels_.size() - 1), uv, weight, out);
  const double t = level - double(fine);
  bilinear_taps(levels_[fine], uint32_t(fine), uv, weight * (1.0 - t), out);
  bilinear_taps(levels_[fine + 1], uint32_t(fine + 1), uv, weight * t, out);
}

void Texture::taps(const glm::dvec2& uv, const glm::dvec2& duv_dx, const glm::dvec2& duv_dy,
                   std::vector<TextureTap>& out) const {
  const Footprint f = footprint(duv_dx, duv_dy);
  for (int i = 0; i < f.probes; ++i)
    trilinear_taps(f.probes == 1 ? uv : uv + f.axis * ((i + 0.5) / f.probes - 0.5), f.level,
                   1.0 / f.probes, out);
}

glm::dvec3 Texture::sample(const glm::dvec2& uv, const glm::dvec2& duv_dx,
                           const glm::dvec2& duv_dy) const {
  const Footprint f = footprint(duv_dx, duv_dy);
  if (f.probes == 1) return trilinear(uv, f.level);
  glm::dvec3 sum(0.0);
  for (int i = 0; i < f.probes; ++i)
    sum += trilinear(uv + f.axis * ((i + 0.5) / f.probes - 0.5), f.level);
  return sum / double(f.probes);
}

}  // namespace countershade
