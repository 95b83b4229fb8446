#pragma once
// How the pixels of a render depend on the texels of its textures.
//
// Radiance is linear in the albedo (diffuse and ambient light are the albedo times the light;
// specular light does not depend on it), and a filtered texture lookup is a weighted sum of
// texels. So with the render's own samples, a pixel's radiance with other texel values is its
// radiance plus Σ w·(change of texel) over the texels its samples read, where w is the samples'
// diffuse light times the lookup's weight, over the pixel's sample count. Once the weights are
// kept, an image with changed texels costs a sum over them instead of a render: texture-filter
// composes every λ of a stimulus set this way (docs/enhancement-methods.md).

#include <cstdint>
#include <glm/vec3.hpp>
#include <memory>
#include <vector>

#include "core/image.h"
#include "enhance/view.h"
#include "render/texture.h"

namespace countershade {

// Per object of `scene`, the index in `textures` of the texture its material samples through its
// UVs, or -1 (no UVs, or a texture not listed).
std::vector<int> texture_of_objects(const Scene& scene,
                                    const std::vector<const Texture*>& textures);

class TexelWeights {
 public:
  // One texel that some pixel reads.
  struct Texel {
    uint32_t texture = 0, level = 0, index = 0;
  };

  // The weights of every sample the view's render took (taken again, from its log where it kept
  // one), for the texels of `textures`; lookups of other textures count as constant light. Null
  // when they would outgrow `byte_limit` (16 bytes per texel per pixel that reads it).
  static std::shared_ptr<const TexelWeights> of_view(const View& view,
                                                     const std::vector<const Texture*>& textures,
                                                     int threads = 0,
                                                     uint64_t byte_limit = kDefaultByteLimit);
  static constexpr uint64_t kDefaultByteLimit = uint64_t(1) << 30;

  // Every texel some pixel reads: the slots of `radiance_with`'s changes.
  const std::vector<Texel>& texels() const { return texels_; }
  // `base` (the view's radiance) plus, per pixel, Σ w·change[slot] over the texels it reads.
  Image radiance_with(const Image& base, const std::vector<glm::dvec3>& change,
                      int threads = 0) const;
  size_t entries() const { return entries_.size(); }

 private:
  struct Entry {
    uint32_t slot = 0;
    float weight[3] = {0, 0, 0};
  };
  class Observer;
  std::vector<Texel> texels_;
  std::vector<size_t> first_;  // per pixel, its entries [first_[p], first_[p + 1])
  std::vector<Entry> entries_;
};

}  // namespace countershade
