#pragma once
// Image files behind a small interface, each codec in a library of its own: OpenImageIO for every
// format (libcountershade_image_codec.so) and libpng for plain PNG files
// (libcountershade_png_codec.so, png_image_codec.cpp says which). OpenImageIO brings about 260
// shared libraries that take 0.3 s of CPU to load; loaded when a command first needs them
// (core/plugin_library.h), they cost nothing to the commands that never do. The interface holds
// only standard types, so that the libraries need nothing of the program.

#include <memory>
#include <string>

namespace countershade::codecs {

// How samples are held in memory: 32-bit float, or 8- or 16-bit codes scaled to the type's range.
enum class Sample { float32, uint8, uint16 };

struct ImageFileSpec {
  int width = 0, height = 0, channels = 0;
  int bits = 0;  // the file's integer bit depth (8, 16, ...), 0 for floating point
};

class ImageFileReader {
 public:
  virtual ~ImageFileReader() = default;
  virtual const ImageFileSpec& spec() const = 0;
  // Reads every channel of every pixel, interleaved, as `sample`; "" or why it failed.
  virtual std::string read(Sample sample, void* pixels) = 0;
};

class ImageCodec {
 public:
  virtual ~ImageCodec() = default;
  // A reader of the file, or none, with why in `error`; an empty `error` means the codec declines
  // the file (another codec may read it).
  virtual std::unique_ptr<ImageFileReader> open(const std::string& path,
                                                std::string& error) const = 0;
  // Whether a file of this name's extension can be written.
  virtual bool writes(const std::string& path) const = 0;
  // Whether this codec writes such pixels (another codec may).
  virtual bool takes(const ImageFileSpec&, Sample) const { return true; }
  // Writes `spec` pixels held as `sample`, as the file's format stores them (`spec.bits` 8 or 16
  // for PNG and TIFF, 0 for float formats). fast_png: zlib level 1 and the `sub` row filter
  // (core/image.cpp says why). "" or why it failed.
  virtual std::string write(const std::string& path, const ImageFileSpec& spec, Sample sample,
                            const void* pixels, bool fast_png) const = 0;
};

}  // namespace countershade::codecs
