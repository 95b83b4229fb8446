#include "core/image.h"

#include <sys/mman.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>

#include "codecs/image_codec.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/file_bytes.h"
#include "core/png_check.h"

namespace countershade {

namespace {

constexpr size_t kHugePage = size_t(2) << 20;

// Freed large buffers kept for the next allocation of the same size: composing λ after λ
// allocates the same buffers again, and a fresh mapping costs the kernel a page clear per 2 MB
// (about 5 ms for a 1920×1080 Lab buffer). At most 4 buffers and 512 MB are kept.
class LargeBufferCache {
 public:
  void* take(size_t rounded) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto it = blocks_.begin(); it != blocks_.end(); ++it)
      if (it->second == rounded) {
        void* p = it->first;
        bytes_ -= rounded;
        blocks_.erase(it);
        return p;
      }
    return nullptr;
  }
  void give(void* p, size_t rounded) {
    std::lock_guard<std::mutex> lock(mutex_);
    while (!blocks_.empty() && (blocks_.size() >= kMaxBlocks || bytes_ + rounded > kMaxBytes)) {
      bytes_ -= blocks_.front().second;
      std::free(blocks_.front().first);
      blocks_.erase(blocks_.begin());
    }
    if (rounded > kMaxBytes) return std::free(p);
    blocks_.emplace_back(p, rounded);
    bytes_ += rounded;
  }

 private:
  static constexpr size_t kMaxBlocks = 4, kMaxBytes = size_t(512) << 20;
  std::mutex mutex_;
  std::vector<std::pair<void*, size_t>> blocks_;  // oldest first
  size_t bytes_ = 0;
};

LargeBufferCache& large_buffers() {
  static auto* cache = new LargeBufferCache;  // never destroyed: buffers may be freed during exit
  return *cache;
}

size_t rounded_to_huge_pages(size_t bytes) {
  return (bytes + kHugePage - 1) / kHugePage * kHugePage;
}

}  // namespace

void* allocate_large(size_t bytes) {
  if (bytes < 2 * kHugePage) {
    void* p = std::malloc(bytes ? bytes : 1);
    if (!p) throw std::bad_alloc();
    return p;
  }
  const size_t rounded = rounded_to_huge_pages(bytes);
  if (void* p = large_buffers().take(rounded)) return p;
  void* p = std::aligned_alloc(kHugePage, rounded);
  if (!p) throw std::bad_alloc();
  ::madvise(p, rounded, MADV_HUGEPAGE);  // a hint; without huge pages the buffer works all the same
  return p;
}

void release_large(void* p, size_t bytes) {
  if (!p) return;
  if (bytes < 2 * kHugePage) return std::free(p);
  large_buffers().give(p, rounded_to_huge_pages(bytes));
}

void check_image_size(const std::filesystem::path& path, long long width, long long height,
                      int channels) {
  constexpr long long kMaxPixels = 16384LL * 16384LL;
  if (width > 65536 || height > 65536 || width * height > kMaxPixels || channels > 16) {
    const double gigabytes = double(width) * double(height) * channels * sizeof(float) / 1e9;
    throw_input_error(path.string(),
                      "image is " + std::to_string(width) + "x" + std::to_string(height) +
                          " with " + std::to_string(channels) + " channels (" +
                          std::to_string(int(gigabytes + 0.5)) +
                          " GB in memory); the limit is 16384x16384 pixels and 16 channels");
  }
}

void check_finite(const std::filesystem::path& path, const Image& image, bool allow_infinity) {
  for (size_t i = 0; i < image.pixels.size(); ++i)
    if (allow_infinity ? std::isnan(image.pixels[i]) : !std::isfinite(image.pixels[i])) {
      const size_t pixel = i / size_t(image.channels);
      throw_input_error(
          path.string(),
          "pixel (" + std::to_string(pixel % size_t(image.width)) + ", " +
              std::to_string(pixel / size_t(image.width)) + ") channel " +
              std::to_string(i % size_t(image.channels)) +
              (allow_infinity ? " is not a number (NaN)" : " is not a finite number"));
    }
}

namespace {

// PFM (portable float map, the Middlebury disparity format): "PF" (RGB) or "Pf" (grey), width,
// height, then a scale whose sign gives the byte order (negative: little-endian), then float rows
// from the bottom of the image to the top.
Image read_pfm(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string magic;
  int width = 0, height = 0;
  double scale = 0;
  if (!(in >> magic >> width >> height >> scale) || (magic != "PF" && magic != "Pf"))
    throw_input_error(path.string(), "not a PFM file (expected a 'PF' or 'Pf' header)");
  if (width <= 0 || height <= 0 || width > 1 << 16 || height > 1 << 16 || scale == 0)
    throw_input_error(path.string(), "invalid PFM header");
  in.get();  // the single whitespace character after the scale
  const int channels = magic == "PF" ? 3 : 1;
  check_image_size(path, width, height, channels);
  // Checked before allocating: a short file's header must not make us zero gigabytes first.
  const uint64_t declared = uint64_t(width) * uint64_t(height) * uint64_t(channels) * 4u;
  const auto header = in.tellg();
  if (header < 0 || std::filesystem::file_size(path) - uint64_t(header) < declared)
    throw_input_error(path.string(), "PFM file is truncated (its header declares " +
                                         std::to_string(width) + "x" + std::to_string(height) +
                                         " pixels, " + std::to_string(declared) +
                                         " bytes of data)");
  Image image(width, height, channels);
  const bool little = scale < 0;
  const bool host_little = std::endian::native == std::endian::little;
  std::vector<char> row(size_t(width) * channels * 4);
  for (int y = height - 1; y >= 0; --y) {
    if (!in.read(row.data(), std::streamsize(row.size())))
      throw_input_error(path.string(), "PFM file is truncated");
    for (size_t k = 0; k < size_t(width) * channels; ++k) {
      char* b = &row[4 * k];
      if (little != host_little) std::reverse(b, b + 4);
      std::memcpy(&image.pixels[size_t(y) * width * channels + k], b, 4);
    }
  }
  check_finite(path, image, true);
  return image;
}

void write_pfm(const std::filesystem::path& path, const Image& image) {
  if (image.channels != 1 && image.channels != 3)
    throw std::runtime_error(path.string() + ": PFM holds 1 or 3 channels");
  std::ofstream out(path, std::ios::binary);
  bool little = std::endian::native == std::endian::little;
  out << (image.channels == 3 ? "PF" : "Pf") << "\n"
      << image.width << " " << image.height << "\n"
      << (little ? "-1.0" : "1.0") << "\n";
  for (int y = image.height - 1; y >= 0; --y)
    out.write(
        reinterpret_cast<const char*>(&image.pixels[size_t(y) * image.width * image.channels]),
        std::streamsize(sizeof(float) * size_t(image.width) * image.channels));
  if (!out) throw std::runtime_error(path.string() + ": write failed");
}

// PNG files are checked chunk by chunk before libpng sees them (see core/png_check.h).
void check_chunks_if_png(const std::filesystem::path& path) {
  char head[8] = {};
  std::ifstream(path, std::ios::binary).read(head, sizeof head);
  if (has_png_signature(std::string_view(head, sizeof head)))
    check_png_chunks(path, read_file_bytes(path));
}

}  // namespace

Image read_image(const std::filesystem::path& path, int* bits) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw_input_error(path.string(), "no such image file");
  if (lower_extension(path) == ".pfm") {
    if (bits) *bits = 0;
    return read_pfm(path);
  }
  check_chunks_if_png(path);
  std::string error;
  const auto in = image_codec().open(path.string(), error);
  if (!in) throw_input_error(path.string(), "cannot read image (" + error + ")");
  const codecs::ImageFileSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.channels <= 0)
    throw_input_error(path.string(), "image is empty");
  check_image_size(path, spec.width, spec.height, spec.channels);
  if (bits) *bits = spec.bits;
  Image image(spec.width, spec.height, spec.channels);
  error = in->read(codecs::Sample::float32, image.pixels.data());
  if (!error.empty()) throw_input_error(path.string(), "cannot decode image (" + error + ")");
  if (spec.bits == 0) check_finite(path, image, true);
  return image;
}

void write_image(const std::filesystem::path& path, const Image& image,
                 const ImageWriteOptions& options) {
  if (image.empty()) throw std::runtime_error(path.string() + ": refusing to write an empty image");
  std::string ext = lower_extension(path);
  if (ext == ".pfm")
    return write_atomically(path,
                            [&](const std::filesystem::path& temp) { write_pfm(temp, image); });
  bool quantised = ext == ".png" || ext == ".tif" || ext == ".tiff";
  if (quantised && options.png_bits != 8 && options.png_bits != 16)
    throw InputError(path.string() + ": bit depth must be 8 or 16");

  write_atomically(path, [&](const std::filesystem::path& temp) {
    const codecs::ImageCodec& codec = image_codec();
    if (!codec.writes(temp.string()))
      throw InputError(path.string() + ": unsupported output format '" + ext + "'");
    const codecs::ImageFileSpec spec{image.width, image.height, image.channels,
                                     quantised ? options.png_bits : 0};
    // Fast zlib level and one row filter: stimuli are written by the thousand and PNG is lossless
    // whatever the settings (level 1: a 1024×768 stimulus takes 84 instead of 243 ms to compose
    // and write, files ~7% larger; the `sub` filter instead of libpng's choice among all five for
    // each row: 29 instead of 44 ms to encode a ritschel2008 stimulus, and files 2–3 % smaller).
    const bool fast_png = ext == ".png";
    std::string error;
    if (!quantised) {
      error =
          codec.write(temp.string(), spec, codecs::Sample::float32, image.pixels.data(), fast_png);
    } else if (options.png_bits == 16) {
      std::vector<uint16_t> codes(image.pixels.size());
      for (size_t i = 0; i < codes.size(); ++i) codes[i] = uint16_t(quantize(image.pixels[i], 16));
      error = codec.write(temp.string(), spec, codecs::Sample::uint16, codes.data(), fast_png);
    } else {
      std::vector<uint8_t> codes(image.pixels.size());
      for (size_t i = 0; i < codes.size(); ++i) codes[i] = uint8_t(quantize(image.pixels[i], 8));
      error = codec.write(temp.string(), spec, codecs::Sample::uint8, codes.data(), fast_png);
    }
    if (!error.empty()) throw std::runtime_error(path.string() + ": " + error);
  });
}

}  // namespace countershade
