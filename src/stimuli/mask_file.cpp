#include "stimuli/mask_file.h"

#include <algorithm>
#include <cstdio>

#include "core/image.h"
#include "core/number_format.h"
#include "core/sha256.h"

namespace countershade {
namespace {

constexpr double kLow = -100.0, kRange = 300.0;

}  // namespace

std::string mask_path(const Experiment& e, const SetUnit& u) {
  const ExperimentMethod& m = e.methods[size_t(u.method)];
  char frame[32];
  std::snprintf(frame, sizeof frame, "/mask/frame-%04d.png", u.frame);
  return e.scenes[u.scene].name + "/" + m.label + "/sigma-" + format_value(m.sigmas[u.sigma]) +
         frame;
}

nlohmann::json write_mask(const std::filesystem::path& dir, const std::string& rel,
                          std::span<const float> mask, int width, int height) {
  Image image(width, height, 1);
  for (size_t i = 0; i < mask.size(); ++i)
    image.pixels[i] = float(std::clamp((double(mask[i]) - kLow) / kRange, 0.0, 1.0));
  std::filesystem::create_directories((dir / rel).parent_path());
  write_image(dir / rel, image, {16});
  return {{"file", rel}, {"sha256", sha256_file(dir / rel)}};
}

std::vector<float> read_mask(const std::filesystem::path& file) {
  const Image image = read_image(file);
  std::vector<float> out(image.pixels.size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = float(kLow + kRange * double(image.pixels[i]));
  return out;
}

}  // namespace countershade
