#pragma once
// Images as the observer sees them: luminance in cd/m² (docs/observer.md, "The model"). PNG,
// TIFF and JPEG codes (8 or 16 bit) go through the display: a calibration's lookup table and
// luminance range, or sRGB up to a peak luminance. PFM, OpenEXR and HDR files hold luminance
// itself. Colour becomes luminance with Rec. 709's weights.

#include <string>

#include "core/display_calibration_file.h"
#include "observer/detection_model.h"

namespace countershade::observer {

struct LuminanceImage {
  int width = 0, height = 0;
  std::vector<double> cd_m2;
};

// An sRGB display from black (0 cd/m²) to `peak` cd/m².
CalibratedDisplay srgb_display(double peak);

// Throws InputError naming the file when it cannot be read or holds a negative luminance.
LuminanceImage read_luminance(const std::string& path, const CalibratedDisplay& display);

// (test − reference) / the reference's mean luminance. Throws InputError naming `test_name` when
// the sizes differ, and `reference_name` when the reference is black.
ContrastImage contrast_between(const LuminanceImage& reference, const LuminanceImage& test,
                               const std::string& reference_name, const std::string& test_name);

}  // namespace countershade::observer
