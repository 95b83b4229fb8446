#include "core/image.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>

#include "core/atomic_file.h"
#include "core/error.h"

namespace countershade {
namespace {

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

}  // namespace

Image read_image(const std::filesystem::path& path, int* bits) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw_input_error(path.string(), "no such image file");
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) {
    std::string message = OIIO::geterror();
    std::replace(message.begin(), message.end(), '\n', ' ');
    throw_input_error(path.string(), "cannot read image (" + message + ")");
  }
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    throw_input_error(path.string(), "image is empty");
  if (bits) *bits = spec.format.is_floating_point() ? 0 : int(spec.format.size() * 8);
  Image image(spec.width, spec.height, spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data())) {
    std::string message = in->geterror();
    std::replace(message.begin(), message.end(), '\n', ' ');
    throw_input_error(path.string(), "cannot decode image (" + message + ")");
  }
  return image;
}

void write_image(const std::filesystem::path& path, const Image& image,
                 const ImageWriteOptions& options) {
  if (image.empty()) throw std::runtime_error(path.string() + ": refusing to write an empty image");
  std::string ext = lower_extension(path);
  bool quantised = ext == ".png" || ext == ".tif" || ext == ".tiff";
  if (quantised && options.png_bits != 8 && options.png_bits != 16)
    throw InputError(path.string() + ": bit depth must be 8 or 16");

  write_atomically(path, [&](const std::filesystem::path& temp) {
    auto out = OIIO::ImageOutput::create(temp.string());
    if (!out) throw InputError(path.string() + ": unsupported output format '" + ext + "'");
    OIIO::TypeDesc type = !quantised ? OIIO::TypeDesc::FLOAT
                          : options.png_bits == 16 ? OIIO::TypeDesc::UINT16
                                                   : OIIO::TypeDesc::UINT8;
    OIIO::ImageSpec spec(image.width, image.height, image.channels, type);
    spec.attribute("Software", "countershade");
    if (!out->open(temp.string(), spec))
      throw std::runtime_error(path.string() + ": cannot open for writing (" + out->geterror() + ")");
    bool ok = false;
    if (!quantised) {
      ok = out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data());
    } else if (options.png_bits == 16) {
      std::vector<uint16_t> codes(image.pixels.size());
      for (size_t i = 0; i < codes.size(); ++i) codes[i] = uint16_t(quantize(image.pixels[i], 16));
      ok = out->write_image(OIIO::TypeDesc::UINT16, codes.data());
    } else {
      std::vector<uint8_t> codes(image.pixels.size());
      for (size_t i = 0; i < codes.size(); ++i) codes[i] = uint8_t(quantize(image.pixels[i], 8));
      ok = out->write_image(OIIO::TypeDesc::UINT8, codes.data());
    }
    if (!ok || !out->close())
      throw std::runtime_error(path.string() + ": write failed (" + out->geterror() + ")");
  });
}

}  // namespace countershade
