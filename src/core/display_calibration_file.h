#pragma once
// The files `countershade calibrate` writes (docs/display.md): the display block with its lookup
// table, and the luminance of code 0 and of full scale. Scenes name one in their display block;
// the image-computable observer reads one to turn codes into cd/m².

#include <filesystem>
#include <string>

#include "core/display.h"
#include "core/json_reader.h"

namespace countershade {

struct CalibratedDisplay {
  DisplayEncoding encoding;                 // the lookup table
  double black_cd_m2 = 0, white_cd_m2 = 0;  // code 0 and full scale

  // The luminance a code value in [0, 1] shows, in cd/m².
  double luminance(double code) const {
    return black_cd_m2 + (white_cd_m2 - black_cd_m2) * encoding.decode(code);
  }
};

// Reads a calibration file; every bad value is an InputError naming the file and the key.
CalibratedDisplay read_calibration_file(const std::filesystem::path& file);

// A lookup table file (code, luminance per row; a header row and # comments allowed), which the
// block `o` names under `key`.
DisplayEncoding read_lut_file(const JsonObject& o, const std::string& key,
                              const std::filesystem::path& file);

}  // namespace countershade
