#include "core/color.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include "test_util.h"

namespace countershade {
namespace {

struct Reference {
  glm::dvec3 srgb, linear;
  Lab lab;
};

// The rows of a numeric CSV under tests/reference/color, after its header.
std::vector<std::vector<double>> read_reference_csv(const std::string& name) {
  std::ifstream in(testing::reference_path("color") / name);
  std::string line;
  std::getline(in, line);
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::stringstream fields(line);
    rows.emplace_back();
    for (std::string f; std::getline(fields, f, ',');) rows.back().push_back(std::stod(f));
  }
  return rows;
}

std::vector<Reference> load_reference() {
  std::vector<Reference> rows;  // srgb_r,srgb_g,srgb_b,linear_r,linear_g,linear_b,L,a,b
  for (const auto& v : read_reference_csv("srgb_to_lab.csv"))
    rows.push_back({{v[0], v[1], v[2]}, {v[3], v[4], v[5]}, {v[6], v[7], v[8]}});
  return rows;
}

TEST(Color, MatchesReferenceSrgbToLab) {
  auto rows = load_reference();
  ASSERT_GT(rows.size(), 200u);
  for (const auto& r : rows) {
    Lab lab = srgb_to_lab(r.srgb);
    double delta_e = std::sqrt(std::pow(lab.L - r.lab.L, 2) + std::pow(lab.a - r.lab.a, 2) +
                               std::pow(lab.b - r.lab.b, 2));
    EXPECT_LT(delta_e, 1e-3) << "sRGB " << r.srgb.x << "," << r.srgb.y << "," << r.srgb.z;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(srgb_decode(r.srgb[c]), r.linear[c], 1e-9);
  }
}

// 300 pairs computed with scikit-image, neutral colours and hue-angle wrap-arounds included.
// The file gives the inputs to 6 decimals, which moves ΔE by up to ~1e-6 of its value; hence a
// tolerance of 1e-6 relative to max(1, ΔE).
TEST(Color, Ciede2000MatchesTheReference) {
  const auto rows = read_reference_csv("ciede2000.csv");  // L1,a1,b1,L2,a2,b2,dE2000
  ASSERT_EQ(rows.size(), 300u);
  for (const auto& v : rows) {
    const Lab first{v[0], v[1], v[2]}, second{v[3], v[4], v[5]};
    const double tolerance = 1e-6 * std::max(1.0, v[6]);
    EXPECT_NEAR(ciede2000(first, second), v[6], tolerance)
        << v[0] << "," << v[1] << "," << v[2] << " / " << v[3];
    EXPECT_NEAR(ciede2000(second, first), v[6], tolerance) << "symmetric";
  }
}

TEST(Color, LabRoundTripsThroughLinearRgb) {
  for (const auto& r : load_reference()) {
    glm::dvec3 back = lab_to_linear_rgb(r.lab);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(back[c], r.linear[c], 1e-6);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(srgb_encode(srgb_decode(r.srgb[c])), r.srgb[c], 1e-12);
  }
}

TEST(Color, LightnessOnlyChangeKeepsHueAndSaturation) {
  Lab lab{50.0, 20.0, -30.0};
  Lab changed = with_lightness(lab, 65.0);
  EXPECT_DOUBLE_EQ(changed.L, 65.0);
  EXPECT_NEAR(std::atan2(changed.b, changed.a), std::atan2(lab.b, lab.a), 1e-12);
  EXPECT_NEAR(std::hypot(changed.a, changed.b) / changed.L, std::hypot(lab.a, lab.b) / lab.L,
              1e-12);
  EXPECT_DOUBLE_EQ(with_lightness(lab, 130.0).L, 100.0);
  EXPECT_DOUBLE_EQ(with_lightness(lab, -5.0).L, 0.0);
  Lab black{0.0, 0.0, 0.0};
  EXPECT_DOUBLE_EQ(with_lightness(black, 10.0).a, 0.0);  // k = 1 when L is ~0
}

}  // namespace
}  // namespace countershade
