#include "runtime/image_decode.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>

#include "codecs/image_codec.h"
#include "core/error.h"
#include "core/image.h"

namespace countershade::runtime {

namespace {

// Decodes into RGBA of type T (read as `type`); grey images fill R, G and B.
template <typename T>
std::vector<T> decode_as(const StimulusImage& image, codecs::Sample sample) {
  std::string error;
  const auto in = image_codec().open(image.file.string(), error);
  if (!in) throw_input_error(image.file.string(), "cannot read the image");
  const codecs::ImageFileSpec& spec = in->spec();
  if (spec.width != image.width || spec.height != image.height)
    throw_input_error(image.file.string(), "the image size differs from the manifest");
  const int n = spec.channels;
  if (n < 1 || n > 4)
    throw_input_error(image.file.string(), "unsupported channel count " + std::to_string(n));
  // A manifest may list sizes up to 2^20; an image that large is refused here, before the
  // allocation would fail (found by fuzz/png_fuzzer.cpp).
  check_image_size(image.file, spec.width, spec.height, n);
  std::vector<T> raw(size_t(spec.width) * size_t(spec.height) * size_t(n));
  error = in->read(sample, raw.data());
  if (!error.empty()) throw_input_error(image.file.string(), "cannot decode: " + error);
  std::vector<T> rgba(size_t(spec.width) * size_t(spec.height) * 4, std::numeric_limits<T>::max());
  for (size_t p = 0; p < size_t(spec.width) * size_t(spec.height); ++p) {
    const T* s = &raw[p * size_t(n)];
    T* d = &rgba[p * 4];
    if (n <= 2)
      d[0] = d[1] = d[2] = s[0];
    else
      d[0] = s[0], d[1] = s[1], d[2] = s[2];
    // Alpha is ignored on purpose: stimuli are shown opaque, exactly as their RGB values.
  }
  return rgba;
}

}  // namespace

std::vector<uint8_t> decode_rgba(const StimulusImage& image) {
  return decode_as<uint8_t>(image, codecs::Sample::uint8);
}

std::vector<uint16_t> decode_rgba16(const StimulusImage& image) {
  return decode_as<uint16_t>(image, codecs::Sample::uint16);
}

namespace {

// Pseudo-grey shows one grey per pixel: a pixel whose R, G and B lie further apart than
// kAchromaticSpread has a colour it cannot show.
void require_achromatic_image(const StimulusImage& image, const std::vector<uint16_t>& rgba) {
  for (size_t p = 0; p < rgba.size() / 4; ++p) {
    const uint16_t* c = &rgba[p * 4];
    if (std::max({c[0], c[1], c[2]}) - std::min({c[0], c[1], c[2]}) <= int(kAchromaticSpread))
      continue;
    throw_input_error(image.file.string(),
                      "--output-path pseudo-grey shows achromatic stimuli only, but pixel (" +
                          std::to_string(p % size_t(image.width)) + ", " +
                          std::to_string(p / size_t(image.width)) +
                          ") has R, G, B = " + std::to_string(c[0]) + ", " + std::to_string(c[1]) +
                          ", " + std::to_string(c[2]) + " (use dither or ten-bit)");
  }
}

}  // namespace

void require_achromatic_images(const Study& study, const OutputPathChoice& path) {
  if (study.bits != 16 || path.automatic || path.path != OutputPath::pseudo_grey) return;
  tbb::parallel_for(size_t(0), study.images.size(), [&](size_t i) {
    require_achromatic_image(study.images[i], decode_rgba16(study.images[i]));
  });
}

namespace {

// The textures, or nothing when the window was closed meanwhile.
std::optional<std::vector<unsigned>> preload_textures(Presenter& presenter, const Study& study) {
  std::vector<unsigned> textures(study.images.size());
  bool closed = false;
  for (size_t first = 0; first < study.images.size() && !closed; first += 8) {
    const size_t last = std::min(first + 8, study.images.size());
    std::vector<std::vector<uint8_t>> pixels8(last - first);
    std::vector<std::vector<uint16_t>> pixels16(last - first);
    tbb::parallel_for(first, last, [&](size_t i) {
      if (study.bits == 16)
        pixels16[i - first] = decode_rgba16(study.images[i]);
      else
        pixels8[i - first] = decode_rgba(study.images[i]);
    });
    for (size_t i = first; i < last; ++i)
      textures[i] = study.bits == 16
                        ? presenter.upload_texture16(pixels16[i - first], study.images[i].width,
                                                     study.images[i].height)
                        : presenter.upload_texture(pixels8[i - first], study.images[i].width,
                                                   study.images[i].height);
    FrameContent loading;
    loading.message = "Loading the stimuli: " + std::to_string(last) + " of " +
                      std::to_string(study.images.size());
    loading.progress = double(last) / double(study.images.size());
    presenter.draw(loading);
    for (const auto& e : presenter.poll_events()) closed |= e.kind == WindowEvent::Kind::close;
  }
  if (closed) return std::nullopt;
  return textures;
}

}  // namespace

Preloaded preload_study(Presenter& presenter, const Study& study) {
  const double start = presenter.now();
  Preloaded out;
  out.textures = preload_textures(presenter, study);
  out.record = Preload{study.images.size(), presenter.now() - start};
  return out;
}

}  // namespace countershade::runtime
