#pragma once
// External images as the image-space commands read them (image-usm, congruence).

#include <string>
#include <vector>

#include "core/image.h"

namespace countershade::cli {

// The image as display code values (sRGB), 3 channels: PNG, TIFF and JPEG as they are, EXR, HDR
// and PFM (linear) encoded. `bits` receives the file's bit depth (0 for float formats).
Image load_display_image(const std::string& path, int& bits);

// Linear depth per pixel from a depth or disparity map of width × height; disparity becomes
// depth ∝ 1/disparity. 0, inf and NaN become 0 (background).
std::vector<float> load_depth(const std::string& path, const std::string& kind, int width,
                              int height);

}  // namespace countershade::cli
