// The image codec library for plain PNG files (libcountershade_png_codec.so) over libpng alone.
//
// Stimuli, references and masks are 8- or 16-bit grey or RGB PNG files. Writing and reading them
// through OpenImageIO loads about 260 shared libraries (0.3 s of CPU) into every command and test
// that touches one; libpng is one. This codec takes only the files whose bytes and pixels it can
// give exactly as OpenImageIO does (tests/codecs/png_codec_test.cpp holds it to that, byte for byte
// and code for code): grey or RGB, 8 or 16 bits, not interlaced, no chunk that could change what
// the pixels mean (palette, transparency, gamma, colour profile, …). It declines the rest, which
// core/image.cpp then gives to OpenImageIO.

#include <png.h>

#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <vector>

#include "codecs/image_codec.h"

namespace countershade::codecs {
namespace {

// libpng reports errors through longjmp; the message is kept for the caller's one line.
struct ErrorState {
  std::jmp_buf jump;
  char message[256] = "";
};

void on_error(png_structp png, png_const_charp message) {
  auto* state = static_cast<ErrorState*>(png_get_error_ptr(png));
  std::snprintf(state->message, sizeof state->message, "%s", message);
  std::longjmp(state->jump, 1);
}

void on_warning(png_structp, png_const_charp) {}  // as OpenImageIO: warnings are not errors

// The chunks that would make OpenImageIO's pixels or metadata differ from the plain samples.
constexpr png_uint_32 kDeclinedChunks =
    PNG_INFO_gAMA | PNG_INFO_sBIT | PNG_INFO_cHRM | PNG_INFO_PLTE | PNG_INFO_tRNS | PNG_INFO_bKGD |
    PNG_INFO_hIST | PNG_INFO_pCAL | PNG_INFO_sRGB | PNG_INFO_iCCP | PNG_INFO_sPLT | PNG_INFO_sCAL;

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

// Converts one row of file samples to the caller's type, as OpenImageIO converts them.
void convert_row(const png_byte* row, int bits, size_t count, Sample sample, void* out) {
  for (size_t i = 0; i < count; ++i) {
    const unsigned code = bits == 8 ? row[i] : unsigned(row[2 * i]) << 8 | row[2 * i + 1];
    if (sample == Sample::float32)
      static_cast<float*>(out)[i] = float(code) * (bits == 8 ? 1.0f / 255.0f : 1.0f / 65535.0f);
    else if (sample == Sample::uint8)
      static_cast<uint8_t*>(out)[i] = uint8_t(bits == 8 ? code : (code + 128u) / 257u);
    else
      static_cast<uint16_t*>(out)[i] = uint16_t(bits == 8 ? code * 257u : code);
  }
}

// libpng's read state over an open file, from its header to its last row. Kept on the heap: libpng
// holds the address of its error state.
struct PngInput {
  File file;
  ErrorState state;
  png_structp png = nullptr;
  png_infop info = nullptr;
  ~PngInput() { png_destroy_read_struct(&png, &info, nullptr); }
};

class PngReader final : public ImageFileReader {
 public:
  PngReader(std::unique_ptr<PngInput> input, const ImageFileSpec& spec)
      : input_(std::move(input)), spec_(spec) {}
  const ImageFileSpec& spec() const override { return spec_; }
  std::string read(Sample sample, void* pixels) override;

 private:
  std::unique_ptr<PngInput> input_;
  ImageFileSpec spec_;
};

// Reads the header of a file this codec takes, leaving libpng at its first row; false otherwise,
// with `declined` set where the codec does not take the file and the reason in the state if not.
bool read_header(PngInput& in, ImageFileSpec& spec, bool& declined) {
  in.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &in.state, on_error, on_warning);
  in.info = in.png ? png_create_info_struct(in.png) : nullptr;
  if (!in.info) {
    std::snprintf(in.state.message, sizeof in.state.message, "out of memory");
    return false;
  }
  if (setjmp(in.state.jump)) return false;
  png_init_io(in.png, in.file.get());
  png_read_info(in.png, in.info);
  const int type = png_get_color_type(in.png, in.info), bits = png_get_bit_depth(in.png, in.info);
  declined = (type != PNG_COLOR_TYPE_GRAY && type != PNG_COLOR_TYPE_RGB) ||
             (bits != 8 && bits != 16) ||
             png_get_interlace_type(in.png, in.info) != PNG_INTERLACE_NONE ||
             png_get_valid(in.png, in.info, kDeclinedChunks) != 0;
  spec = {int(png_get_image_width(in.png, in.info)), int(png_get_image_height(in.png, in.info)),
          type == PNG_COLOR_TYPE_RGB ? 3 : 1, bits};
  return !declined;
}

// Reads every row into `pixels` as `sample`, through `row`. libpng's errors return through the
// state's jump, so nothing here may need a destructor.
void read_rows(PngInput& in, const ImageFileSpec& spec, png_byte* row, Sample sample,
               void* pixels) {
  const size_t samples = size_t(spec.width) * size_t(spec.channels);
  const size_t size = sample == Sample::float32 ? 4 : sample == Sample::uint16 ? 2 : 1;
  for (int y = 0; y < spec.height; ++y) {
    png_read_row(in.png, row, nullptr);
    convert_row(row, spec.bits, samples, sample,
                static_cast<char*>(pixels) + size_t(y) * samples * size);
  }
  png_read_end(in.png, nullptr);
}

std::string PngReader::read(Sample sample, void* pixels) {
  std::vector<png_byte> row(size_t(spec_.width) * size_t(spec_.channels) * size_t(spec_.bits / 8));
  if (setjmp(input_->state.jump)) return input_->state.message;
  read_rows(*input_, spec_, row.data(), sample, pixels);
  return "";
}

// Writes the chunks OpenImageIO writes for such an image: IHDR, oFFs (0, 0), the Software text,
// the image data with its zlib settings, IEND.
std::string write_png(std::FILE* file, const ImageFileSpec& spec, const void* pixels,
                      bool fast_png) {
  ErrorState state;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &state, on_error, on_warning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    return "out of memory";
  }
  const size_t row_bytes = size_t(spec.width) * size_t(spec.channels) * size_t(spec.bits / 8);
  std::vector<png_byte> row(spec.bits == 16 ? row_bytes : 0);
  if (setjmp(state.jump)) {
    png_destroy_write_struct(&png, &info);
    return std::string("write failed (") + state.message + ")";
  }
  png_init_io(png, file);
  png_set_compression_level(png, fast_png ? 1 : 6);
  png_set_compression_strategy(png, 0);  // Z_DEFAULT_STRATEGY
  png_set_IHDR(png, info, png_uint_32(spec.width), png_uint_32(spec.height), spec.bits,
               spec.channels == 3 ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_oFFs(png, info, 0, 0, PNG_OFFSET_PIXEL);
  png_text software{};
  software.compression = PNG_TEXT_COMPRESSION_NONE;
  software.key = const_cast<char*>("Software");
  software.text = const_cast<char*>("countershade");
  png_set_text(png, info, &software, 1);
  if (fast_png) png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
  png_write_info(png, info);
  for (int y = 0; y < spec.height; ++y) {
    const auto* source = static_cast<const png_byte*>(pixels) + size_t(y) * row_bytes;
    if (spec.bits == 8) {
      png_write_row(png, source);
      continue;
    }
    for (size_t i = 0; i < row_bytes; i += 2) {  // PNG stores 16-bit samples big-endian
      row[i] = source[i + 1];
      row[i + 1] = source[i];
    }
    png_write_row(png, row.data());
  }
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return "";
}

bool has_png_extension(const std::string& path) {
  if (path.size() < 4) return false;
  std::string ext = path.substr(path.size() - 4);
  for (char& c : ext) c = char(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  return ext == ".png";
}

class PngCodec final : public ImageCodec {
 public:
  std::unique_ptr<ImageFileReader> open(const std::string& path,
                                        std::string& error) const override {
    auto in = std::make_unique<PngInput>();
    in->file.reset(std::fopen(path.c_str(), "rb"));
    if (!in->file) {
      error = "cannot open for reading (" + std::string(std::strerror(errno)) + ")";
      return nullptr;
    }
    // A file of another format under a .png name is OpenImageIO's to read, as it always was.
    png_byte signature[8] = {};
    if (std::fread(signature, 1, 8, in->file.get()) != 8 || png_sig_cmp(signature, 0, 8) != 0) {
      error.clear();
      return nullptr;
    }
    std::rewind(in->file.get());
    ImageFileSpec spec;
    bool declined = false;
    if (read_header(*in, spec, declined)) return std::make_unique<PngReader>(std::move(in), spec);
    error = declined ? "" : in->state.message;
    return nullptr;
  }

  bool writes(const std::string& path) const override { return has_png_extension(path); }

  bool takes(const ImageFileSpec& spec, Sample sample) const override {
    return (spec.channels == 1 || spec.channels == 3) &&
           ((spec.bits == 8 && sample == Sample::uint8) ||
            (spec.bits == 16 && sample == Sample::uint16));
  }

  std::string write(const std::string& path, const ImageFileSpec& spec, Sample sample,
                    const void* pixels, bool fast_png) const override {
    if (!takes(spec, sample)) return "the PNG codec takes 8- or 16-bit grey or RGB samples only";
    File file(std::fopen(path.c_str(), "wb"));
    if (!file) return "cannot open for writing (" + std::string(std::strerror(errno)) + ")";
    std::string error = write_png(file.get(), spec, pixels, fast_png);
    if (std::fclose(file.release()) != 0 && error.empty()) error = "write failed";
    return error;
  }
};

}  // namespace
}  // namespace countershade::codecs

extern "C" __attribute__((visibility("default"))) void* countershade_png_codec() {
  static countershade::codecs::PngCodec codec;
  return static_cast<countershade::codecs::ImageCodec*>(&codec);
}
