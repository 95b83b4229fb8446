// The image codec library (codecs/image_codec.h) over OpenImageIO.

#include <OpenImageIO/imageio.h>

#include <algorithm>

#include "codecs/image_codec.h"

namespace countershade::codecs {
namespace {

OIIO::TypeDesc type_of(Sample sample) {
  switch (sample) {
    case Sample::uint8:
      return OIIO::TypeDesc::UINT8;
    case Sample::uint16:
      return OIIO::TypeDesc::UINT16;
    default:
      return OIIO::TypeDesc::FLOAT;
  }
}

// OpenImageIO's messages can span lines; ours are one line each.
std::string one_line(std::string message) {
  std::replace(message.begin(), message.end(), '\n', ' ');
  return message;
}

class OiioReader final : public ImageFileReader {
 public:
  explicit OiioReader(std::unique_ptr<OIIO::ImageInput> in) : in_(std::move(in)) {
    const OIIO::ImageSpec& s = in_->spec();
    spec_ = {s.width, s.height, s.nchannels,
             s.format.is_floating_point() ? 0 : int(s.format.size() * 8)};
  }
  const ImageFileSpec& spec() const override { return spec_; }
  std::string read(Sample sample, void* pixels) override {
    if (in_->read_image(0, 0, 0, spec_.channels, type_of(sample), pixels)) return "";
    const std::string why = one_line(in_->geterror());
    return why.empty() ? "cannot decode" : why;
  }

 private:
  std::unique_ptr<OIIO::ImageInput> in_;
  ImageFileSpec spec_;
};

class OiioCodec final : public ImageCodec {
 public:
  std::unique_ptr<ImageFileReader> open(const std::string& path,
                                        std::string& error) const override {
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
      error = one_line(OIIO::geterror());
      return nullptr;
    }
    return std::make_unique<OiioReader>(std::move(in));
  }

  bool writes(const std::string& path) const override {
    return OIIO::ImageOutput::create(path) != nullptr;
  }

  std::string write(const std::string& path, const ImageFileSpec& spec, Sample sample,
                    const void* pixels, bool fast_png) const override {
    auto out = OIIO::ImageOutput::create(path);
    if (!out) return "unsupported output format";
    const OIIO::TypeDesc stored = spec.bits == 16  ? OIIO::TypeDesc::UINT16
                                  : spec.bits == 8 ? OIIO::TypeDesc::UINT8
                                                   : OIIO::TypeDesc::FLOAT;
    OIIO::ImageSpec s(spec.width, spec.height, spec.channels, stored);
    s.attribute("Software", "countershade");
    if (fast_png) {
      s.attribute("png:compressionLevel", 1);
      s.attribute("png:filter", 0x10);  // PNG_FILTER_SUB
    }
    if (!out->open(path, s)) return "cannot open for writing (" + one_line(out->geterror()) + ")";
    if (!out->write_image(type_of(sample), pixels) || !out->close())
      return "write failed (" + one_line(out->geterror()) + ")";
    return "";
  }
};

}  // namespace
}  // namespace countershade::codecs

extern "C" __attribute__((visibility("default"))) void* countershade_image_codec() {
  static countershade::codecs::OiioCodec codec;
  return static_cast<countershade::codecs::ImageCodec*>(&codec);
}
