#include "enhance/filtered_pyramid.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <glm/common.hpp>
#include <sstream>

#include "core/atomic_file.h"
#include "core/color.h"
#include "core/file_bytes.h"
#include "core/sha256.h"

namespace countershade {
namespace fs = std::filesystem;
namespace {

constexpr const char* kCacheMagic = "countershade-lightness-detail 1\n";

std::string cache_key(const Texture& plain, TextureMode mode, const LightnessFilter& f) {
  Sha256 hash;
  const TextureLevel& base = plain.levels().front();
  std::ostringstream inputs;
  inputs.precision(17);
  inputs << kCacheMagic << base.width << ' ' << base.height << ' '
         << (mode == TextureMode::mip ? "mip" : "texture") << ' ' << filter_name(f.kind) << ' '
         << f.sigma << ' ' << f.sigma_r << ' ' << f.tau << ' ' << f.phi << '\n';
  hash.update(inputs.str());
  hash.update(base.texels.data(), base.texels.size() * sizeof(glm::vec3));
  return hash.hex_digest();
}

std::optional<std::vector<std::vector<float>>> read_cached(const fs::path& file,
                                                           const FilteredPyramid& p,
                                                           size_t levels) {
  std::error_code error;
  if (!fs::is_regular_file(file, error)) return std::nullopt;
  std::string bytes;
  try {
    bytes = read_file_bytes(file);
  } catch (const std::exception&) {
    return std::nullopt;  // unreadable: recomputed like a damaged file
  }
  const size_t magic = std::strlen(kCacheMagic);
  if (bytes.compare(0, magic, kCacheMagic) != 0) return std::nullopt;
  std::vector<std::vector<float>> detail(levels);
  size_t at = magic;
  for (size_t k = 0; k < levels; ++k) {
    detail[k].resize(p.plain->levels()[k].texels.size());
    const size_t size = detail[k].size() * sizeof(float);
    if (bytes.size() < at + size) return std::nullopt;  // a damaged file is recomputed
    std::memcpy(detail[k].data(), bytes.data() + at, size);
    at += size;
  }
  if (at != bytes.size()) return std::nullopt;
  return detail;
}

void write_cached(const fs::path& file, const std::vector<std::vector<float>>& detail) {
  std::string bytes = kCacheMagic;
  for (const auto& level : detail)
    bytes.append(reinterpret_cast<const char*>(level.data()), level.size() * sizeof(float));
  std::error_code error;
  fs::create_directories(file.parent_path(), error);
  try {
    write_text_atomically(file, bytes);
  } catch (const std::exception&) {
    // A cache that cannot be written only costs the next run the filtering again.
  }
}

}  // namespace

std::vector<float> level_lightness(const TextureLevel& level) {
  std::vector<float> L(level.texels.size());
  for (size_t i = 0; i < L.size(); ++i)
    L[i] = float(linear_rgb_to_lab(glm::dvec3(level.texels[i])).L);
  return L;
}

glm::vec3 texel_with_detail(const glm::vec3& plain, double change) {
  if (change == 0.0) return plain;
  const Lab lab = linear_rgb_to_lab(glm::dvec3(plain));
  const glm::dvec3 rgb = lab_to_linear_rgb(with_lightness(lab, lab.L + change));
  return glm::vec3(glm::clamp(rgb, glm::dvec3(0.0), glm::dvec3(1.0)));
}

TextureLevel with_detail(const TextureLevel& plain, const std::vector<float>& detail,
                         double strength) {
  TextureLevel out = plain;
  for (size_t i = 0; i < out.texels.size(); ++i)
    out.texels[i] = texel_with_detail(plain.texels[i], strength * double(detail[i]));
  return out;
}

Texture FilteredPyramid::relative_detail() const {
  std::vector<TextureLevel> levels;
  for (size_t k = 0; k < detail.size(); ++k) {
    const TextureLevel& level = plain->levels()[k];
    const std::vector<float> L = level_lightness(level);
    TextureLevel relative{level.width, level.height, std::vector<glm::vec3>(L.size())};
    const double strength = mode == TextureMode::mip ? strength_of_level(k) : 1.0;
    for (size_t i = 0; i < L.size(); ++i)
      relative.texels[i] = glm::vec3(float(strength * detail[k][i] / (L[i] + 16.0)));
    levels.push_back(std::move(relative));
  }
  if (mode == TextureMode::texture) return Texture(std::move(levels.front()));
  return Texture::from_levels(std::move(levels));
}

glm::vec3 FilteredPyramid::mip_texel_at(double lambda, size_t level, size_t index) const {
  return texel_with_detail(plain->levels()[level].texels[index],
                           lambda * strength_of_level(level) * double(detail[level][index]));
}

double FilteredPyramid::strength_of_level(size_t level) const {
  if (level_strengths.empty()) return 1.0;
  return level_strengths[std::min(level, level_strengths.size() - 1)];
}

Texture FilteredPyramid::at(double lambda) const {
  if (mode == TextureMode::texture)
    return Texture(with_detail(plain->levels().front(), detail.front(), lambda));
  std::vector<TextureLevel> levels;
  for (size_t k = 0; k < detail.size(); ++k)
    levels.push_back(with_detail(plain->levels()[k], detail[k], lambda * strength_of_level(k)));
  return Texture::from_levels(std::move(levels));
}

std::optional<fs::path> pyramid_cache_folder() {
  if (const char* c = std::getenv("COUNTERSHADE_CACHE"); c && *c) return fs::path(c);
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return fs::path(x) / "countershade";
  if (const char* h = std::getenv("HOME"); h && *h) return fs::path(h) / ".cache" / "countershade";
  return std::nullopt;
}

FilteredPyramid filter_pyramid(std::shared_ptr<const Texture> plain, TextureMode mode,
                               const LightnessFilter& filter, std::vector<double> level_strengths,
                               const std::optional<fs::path>& cache, int threads) {
  FilteredPyramid p{std::move(plain), mode, {}, std::move(level_strengths)};
  const size_t levels = mode == TextureMode::mip ? p.plain->levels().size() : 1;
  const std::optional<fs::path> file =
      cache ? std::optional<fs::path>(*cache / "pyramids" /
                                      (cache_key(*p.plain, mode, filter) + ".detail"))
            : std::nullopt;
  if (file)
    if (auto cached = read_cached(*file, p, levels)) {
      p.detail = std::move(*cached);
      return p;
    }
  for (size_t k = 0; k < levels; ++k) {
    const TextureLevel& level = p.plain->levels()[k];
    p.detail.push_back(lightness_detail(level_lightness(level), level.width, level.height, filter,
                                        Borders::wrap, threads));
  }
  if (file) write_cached(*file, p.detail);
  return p;
}

}  // namespace countershade
