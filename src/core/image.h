#pragma once
// A plain float image and its file I/O through OpenImageIO.

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace countershade {

// An allocator whose containers leave new floats uninitialised unless a value is given, so an
// image that is about to be overwritten entirely is not filled first (tens of MB per λ).
template <class T>
struct DefaultInitAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  using std::allocator<T>::allocator;
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    if constexpr (sizeof...(Args) == 0)
      ::new (static_cast<void*>(p)) U;
    else
      ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

using PixelVector = std::vector<float, DefaultInitAllocator<float>>;
using PixelDoubles = std::vector<double, DefaultInitAllocator<double>>;

// Memory for a buffer of `bytes`, in huge pages where it is large; release with release_large,
// which keeps a few large buffers for reuse by the next allocation of the same size.
void* allocate_large(size_t bytes);
void release_large(void* p, size_t bytes);

// The same for aggregates of numbers that have default member values (such as Lab): a buffer
// that is about to be overwritten is left as it is, not filled with those values.
template <class T>
struct UninitializedAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = UninitializedAllocator<U>;
  };
  using std::allocator<T>::allocator;
  // Large buffers in transparent huge pages: a fresh 50 MB buffer then faults in 25 pages, not
  // 12,000 (about 30 ms on the reference machine).
  T* allocate(size_t n) { return static_cast<T*>(allocate_large(n * sizeof(T))); }
  void deallocate(T* p, size_t n) { release_large(p, n * sizeof(T)); }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    if constexpr (sizeof...(Args) > 0) ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

// Row-major, interleaved channels, top row first.
struct Image {
  int width = 0, height = 0, channels = 0;
  PixelVector pixels;

  // Tag for an image whose every pixel the caller writes before reading any.
  struct Uninitialized {};

  Image() = default;
  Image(int w, int h, int c, float fill = 0.0f)
      : width(w), height(h), channels(c), pixels(size_t(w) * size_t(h) * size_t(c), fill) {}
  Image(int w, int h, int c, Uninitialized)
      : width(w), height(h), channels(c), pixels(size_t(w) * size_t(h) * size_t(c)) {}

  size_t index(int x, int y, int c = 0) const {
    return (size_t(y) * size_t(width) + size_t(x)) * size_t(channels) + size_t(c);
  }
  float& at(int x, int y, int c = 0) { return pixels[index(x, y, c)]; }
  float at(int x, int y, int c = 0) const { return pixels[index(x, y, c)]; }
  bool empty() const { return pixels.empty(); }
};

struct ImageWriteOptions {
  int png_bits = 8;  // 8 or 16; PNG and TIFF values are code values in [0,1]
};

namespace codecs {
class ImageCodec;
}
// Every image format: libpng for plain PNG files, OpenImageIO for the rest, each loaded on first
// use (core/image_codecs.cpp).
const codecs::ImageCodec& image_codec();

// Reads any format OpenImageIO knows (PNG, EXR, TIFF, PFM, HDR, ...) as float. Integer formats
// come back scaled to [0,1]. Throws InputError naming the file when it cannot be read.
// `bits`, when given, receives the file's integer bit depth (8, 16, ...) or 0 for float formats.
// Refuses images over 16384x16384 pixels before allocating them, and NaN in float images
// (+inf stays: depth maps mark the background with it; radiance readers call check_finite).
Image read_image(const std::filesystem::path& path, int* bits = nullptr);
void check_image_size(const std::filesystem::path& path, long long width, long long height,
                      int channels);
// Throws InputError naming the first pixel and channel that is NaN or (unless allowed) infinite.
void check_finite(const std::filesystem::path& path, const Image& image,
                  bool allow_infinity = false);

// Writes by extension: .png/.tif/.tiff quantised (round to nearest) to 8 or 16 bits, .exr/.pfm/.hdr
// as float. The file appears atomically: a temporary file in the same folder, then a rename.
void write_image(const std::filesystem::path& path, const Image& image,
                 const ImageWriteOptions& options = {});

// Quantises a [0,1] value to an n-bit integer code by rounding to nearest.
inline uint32_t quantize(float value, int bits) {
  float max_code = float((1u << bits) - 1u);
  float v = value != value ? 0.0f : (value < 0.0f ? 0.0f : (value > 1.0f ? 1.0f : value));
  return uint32_t(v * max_code + 0.5f);
}

}  // namespace countershade
