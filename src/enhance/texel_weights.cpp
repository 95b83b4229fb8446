#include "enhance/texel_weights.h"

#include <algorithm>
#include <atomic>

#include "core/parallel.h"
#include "render/pixel_pass.h"
#include "render/shading.h"

namespace countershade {

// In a named namespace, not an anonymous one: TexelWeights::Observer, a class of the header,
// holds it.
namespace texel_weights_detail {
// One texel's weight in a pixel: the texel's id over every texture's levels, and the diffuse light
// that reaches the pixel through it (single precision, as kept: 16 bytes).
struct Weighed {
  uint32_t id = 0;
  float weight[3] = {0, 0, 0};
};
}  // namespace texel_weights_detail

namespace {

using texel_weights_detail::Weighed;

// The weights of the pixel being seen, summed per texel id (open addressing; one per thread, as a
// thread sees one pixel at a time).
class PixelSums {
 public:
  void add(uint32_t id, const glm::dvec3& weight) {
    if (2 * (used_.size() + 1) > keys_.size()) grow();
    size_t at = slot_of(id);
    if (keys_[at] != id) {
      keys_[at] = id;
      sums_[at] = glm::dvec3(0.0);
      used_.push_back(uint32_t(at));
    }
    sums_[at] += weight;
  }
  // The sums over `samples`, sorted by id; the table is left empty.
  std::vector<Weighed> take(uint32_t samples) {
    std::vector<Weighed> out;
    out.reserve(used_.size());
    for (uint32_t at : used_) {
      const glm::dvec3 w = sums_[at] / double(samples);
      out.push_back({keys_[at], {float(w.x), float(w.y), float(w.z)}});
      keys_[at] = kEmpty;
    }
    used_.clear();
    std::sort(out.begin(), out.end(),
              [](const Weighed& a, const Weighed& b) { return a.id < b.id; });
    return out;
  }

 private:
  static constexpr uint32_t kEmpty = ~0u;
  size_t slot_of(uint32_t id) const {
    const size_t mask = keys_.size() - 1;
    size_t at = (size_t(id) * 0x9E3779B1u) & mask;
    while (keys_[at] != kEmpty && keys_[at] != id) at = (at + 1) & mask;
    return at;
  }
  void grow() {
    std::vector<std::pair<uint32_t, glm::dvec3>> kept;
    for (uint32_t at : used_) kept.emplace_back(keys_[at], sums_[at]);
    keys_.assign(std::max<size_t>(256, 2 * keys_.size()), kEmpty);
    sums_.resize(keys_.size());
    used_.clear();
    for (const auto& [id, sum] : kept) {
      const size_t at = slot_of(id);
      keys_[at] = id;
      sums_[at] = sum;
      used_.push_back(uint32_t(at));
    }
  }
  std::vector<uint32_t> keys_, used_;
  std::vector<glm::dvec3> sums_;
};

thread_local PixelSums pixel_sums;

}  // namespace

class TexelWeights::Observer final : public SampleObserver {
 public:
  Observer(const Scene& scene, const std::vector<const Texture*>& textures, size_t pixels,
           uint64_t entry_limit)
      : textures_(textures),
        texture_of_(texture_of_objects(scene, textures)),
        merged_(pixels),
        entry_limit_(entry_limit) {
    for (const Object& o : scene.objects) repeat_.push_back(o.material.texture_repeat);
    for (const Texture* t : textures) {
      first_id_.emplace_back();
      for (const TextureLevel& level : t->levels()) {
        first_id_.back().push_back(ids_);
        ids_ += uint32_t(level.texels.size());
      }
    }
  }

  void surface(size_t /*pixel*/, const Shader& shader, const SurfacePoint& point,
               const ShadingRecord& record, const LightSampleRecord* lights) override {
    const int k = texture_of_[point.object];
    if (k < 0 || over_limit()) return;
    // Radiance is linear in the albedo, per channel: this is the light each unit of albedo
    // reflects.
    const glm::dvec3 light = shader.evaluate(point, record, lights, glm::dvec3(1.0)) -
                             shader.evaluate(point, record, lights, glm::dvec3(0.0));
    thread_local std::vector<TextureTap> taps;
    taps.clear();
    const double repeat = repeat_[point.object];
    textures_[size_t(k)]->taps(point.uv * repeat, point.duv_dx * repeat, point.duv_dy * repeat,
                               taps);
    for (const TextureTap& tap : taps)
      pixel_sums.add(first_id_[size_t(k)][tap.level] + tap.texel, light * tap.weight);
  }

  // Past the limit the weights are given up. The running total only grows, so whether that happens
  // depends on the samples alone, not on the order the threads finish their pixels.
  void pixel_done(size_t pixel, uint32_t samples) override {
    std::vector<Weighed> weights = pixel_sums.take(std::max(samples, 1u));
    if (over_limit()) return;
    if ((entries_ += weights.size()) > entry_limit_) {
      over_ = true;
      return;
    }
    merged_[pixel] = std::move(weights);
  }
  bool over_limit() const { return over_.load(std::memory_order_relaxed); }

  // The weights, with every id read given a slot (in id order).
  void finish(TexelWeights& out, int threads) {
    std::vector<int32_t> slot(ids_, -1);
    for (const auto& pixel : merged_)
      for (const Weighed& w : pixel) slot[w.id] = 0;
    for (uint32_t id = 0; id < ids_; ++id)
      if (slot[id] == 0) {
        slot[id] = int32_t(out.texels_.size());
        out.texels_.push_back(texel_of(id));
      }
    out.first_.assign(merged_.size() + 1, 0);
    for (size_t p = 0; p < merged_.size(); ++p)
      out.first_[p + 1] = out.first_[p] + merged_[p].size();
    out.entries_.resize(out.first_.back());
    parallel_ranges(
        merged_.size(), threads,
        [&](size_t begin, size_t end) {
          for (size_t p = begin; p < end; ++p) {
            Entry* entry = out.entries_.data() + out.first_[p];
            for (const Weighed& w : merged_[p])
              *entry++ = {uint32_t(slot[w.id]), {w.weight[0], w.weight[1], w.weight[2]}};
            std::vector<Weighed>().swap(merged_[p]);
          }
        },
        1024);
  }

 private:
  Texel texel_of(uint32_t id) const {
    for (uint32_t k = 0; k < first_id_.size(); ++k)
      for (uint32_t level = uint32_t(first_id_[k].size()); level-- > 0;)
        if (id >= first_id_[k][level]) return {k, level, id - first_id_[k][level]};
    return {};
  }

  const std::vector<const Texture*>& textures_;
  std::vector<int> texture_of_;  // per object: index into textures_, or -1
  std::vector<double> repeat_;
  std::vector<std::vector<uint32_t>> first_id_;  // [texture][level]
  uint32_t ids_ = 0;
  std::vector<std::vector<Weighed>> merged_;  // per pixel
  uint64_t entry_limit_;
  std::atomic<uint64_t> entries_{0};
  std::atomic<bool> over_{false};
};

std::vector<int> texture_of_objects(const Scene& scene,
                                    const std::vector<const Texture*>& textures) {
  std::vector<int> out;
  for (const Object& o : scene.objects) {
    const auto found = std::find(textures.begin(), textures.end(), o.material.texture.get());
    out.push_back(o.mesh.has_uvs() && found != textures.end() ? int(found - textures.begin()) : -1);
  }
  return out;
}

std::shared_ptr<const TexelWeights> TexelWeights::of_view(
    const View& view, const std::vector<const Texture*>& textures, int threads,
    uint64_t byte_limit) {
  const Scene& scene = *view.scene;
  Observer observer(scene, textures, view.render.spp.size(), byte_limit / sizeof(Entry));
  observe_samples(scene, *view.tracer, view.render.spp, view.render.trace.get(), observer, threads);
  if (observer.over_limit()) return nullptr;
  auto out = std::make_shared<TexelWeights>();
  observer.finish(*out, threads);
  return out;
}

Image TexelWeights::radiance_with(const Image& base, const std::vector<glm::dvec3>& change,
                                  int threads) const {
  Image out = base;
  parallel_ranges(
      first_.size() - 1, threads,
      [&](size_t begin, size_t end) {
        for (size_t p = begin; p < end; ++p) {
          if (first_[p] == first_[p + 1]) continue;
          glm::dvec3 sum(0.0);
          for (size_t e = first_[p]; e < first_[p + 1]; ++e) {
            const Entry& entry = entries_[e];
            sum +=
                glm::dvec3(entry.weight[0], entry.weight[1], entry.weight[2]) * change[entry.slot];
          }
          for (int c = 0; c < 3; ++c)
            out.pixels[3 * p + size_t(c)] = float(double(base.pixels[3 * p + size_t(c)]) + sum[c]);
        }
      },
      1024);
  return out;
}

}  // namespace countershade
