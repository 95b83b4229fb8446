#include "core/display_calibration_file.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "core/error.h"

namespace countershade {

namespace fs = std::filesystem;

CalibratedDisplay read_calibration_file(const fs::path& file) {
  const nlohmann::json j = parse_json_file(file);
  const JsonObject c(j, file.string(), "");
  const JsonObject block = c.object("display");
  if (block.string("encoding") != "lut")
    block.fail("encoding", "expected \"lut\" (a file written by countershade calibrate)");
  fs::path lut = block.string("lut");
  if (lut.is_relative()) lut = file.parent_path() / lut;
  CalibratedDisplay out;
  out.encoding = read_lut_file(block, "lut", lut);
  const JsonObject range = c.object("luminance_cd_m2");
  out.black_cd_m2 = range.number("black");
  out.white_cd_m2 = range.number("white");
  if (!(out.black_cd_m2 >= 0 && out.white_cd_m2 > out.black_cd_m2))
    range.fail("white", "expected 0 ≤ black < white");
  return out;
}

DisplayEncoding read_lut_file(const JsonObject& o, const std::string& key, const fs::path& file) {
  std::ifstream in(file);
  if (!in) o.fail(key, "cannot read lookup table '" + file.string() + "'");
  std::vector<double> codes, luminances;
  std::string line;
  size_t number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream fields(line);
    double code, lum;
    if (!(fields >> code >> lum)) {
      if (codes.empty() && number == 1) continue;  // header row
      throw_input_error(file.string() + ": line " + std::to_string(number),
                        "expected two numbers: code, luminance");
    }
    codes.push_back(code);
    luminances.push_back(lum);
  }
  try {
    return DisplayEncoding::lut(codes, luminances);
  } catch (const InputError& e) {
    throw_input_error(file.string(), e.what());
  }
}

}  // namespace countershade
