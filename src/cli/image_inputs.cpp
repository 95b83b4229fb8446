#include "cli/image_inputs.h"

#include <algorithm>
#include <cmath>

#include "core/atomic_file.h"
#include "core/color.h"
#include "core/error.h"

namespace countershade::cli {
namespace {

bool is_linear_format(const std::string& ext) {
  return ext == ".exr" || ext == ".hdr" || ext == ".pfm";
}

}  // namespace

Image load_display_image(const std::string& path, int& bits) {
  Image in = read_image(path, &bits);
  bool linear = is_linear_format(lower_extension(path));
  Image rgb(in.width, in.height, 3);
  for (int y = 0; y < in.height; ++y)
    for (int x = 0; x < in.width; ++x)
      for (int c = 0; c < 3; ++c) {
        float v = in.at(x, y, in.channels >= 3 ? c : 0);
        if (!std::isfinite(v))
          throw_input_error(
              path, "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") is not finite");
        rgb.at(x, y, c) = linear ? float(srgb_encode(std::clamp(double(v), 0.0, 1.0)))
                                 : std::clamp(v, 0.0f, 1.0f);
      }
  return rgb;
}

std::vector<float> load_depth(const std::string& path, const std::string& kind, int width,
                              int height) {
  Image map = read_image(path);
  if (map.width != width || map.height != height)
    throw_input_error(path, "depth map is " + std::to_string(map.width) + "x" +
                                std::to_string(map.height) + " but the image is " +
                                std::to_string(width) + "x" + std::to_string(height));
  std::vector<float> depth(size_t(width) * height);
  for (size_t i = 0; i < depth.size(); ++i) {
    float v = map.pixels[i * size_t(map.channels)];
    bool valid = std::isfinite(v) && v > 0.0f;
    depth[i] = !valid ? 0.0f : (kind == "disparity" ? 1.0f / v : v);
  }
  return depth;
}

}  // namespace countershade::cli
