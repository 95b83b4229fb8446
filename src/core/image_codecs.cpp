// The codec that reads or writes an image file: libpng for the plain PNG files it takes (most
// stimuli), OpenImageIO for everything else (codecs/image_codec.h). Each library loads when a file
// first needs it, so that a command reading and writing plain PNG files never loads OpenImageIO.

#include <memory>
#include <string>

#include "codecs/image_codec.h"
#include "core/atomic_file.h"
#include "core/image.h"
#include "core/plugin_library.h"

namespace countershade {
namespace {

const codecs::ImageCodec& openimageio() { return plugin<codecs::ImageCodec>("image_codec"); }
const codecs::ImageCodec& libpng() { return plugin<codecs::ImageCodec>("png_codec"); }

bool is_png_name(const std::string& path) { return lower_extension(path) == ".png"; }

class ChosenCodec final : public codecs::ImageCodec {
 public:
  std::unique_ptr<codecs::ImageFileReader> open(const std::string& path,
                                                std::string& error) const override {
    if (is_png_name(path)) {
      auto reader = libpng().open(path, error);
      if (reader || !error.empty()) return reader;  // read, or refused: not declined
    }
    return openimageio().open(path, error);
  }

  bool writes(const std::string& path) const override {
    return is_png_name(path) || openimageio().writes(path);
  }

  std::string write(const std::string& path, const codecs::ImageFileSpec& spec,
                    codecs::Sample sample, const void* pixels, bool fast_png) const override {
    if (is_png_name(path) && libpng().takes(spec, sample))
      return libpng().write(path, spec, sample, pixels, fast_png);
    return openimageio().write(path, spec, sample, pixels, fast_png);
  }
};

}  // namespace

const codecs::ImageCodec& image_codec() {
  static const ChosenCodec codec;
  return codec;
}

}  // namespace countershade
