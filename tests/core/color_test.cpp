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

std::vector<Reference> load_reference() {
  std::ifstream in(testing::shared_dir() / "reference/color/srgb_to_lab.csv");
  std::string line;
  std::getline(in, line);  // header: srgb_r,srgb_g,srgb_b,linear_r,linear_g,linear_b,L,a,b
  std::vector<Reference> rows;
  while (std::getline(in, line)) {
    std::stringstream fields(line);
    double v[9];
    for (double& x : v) {
      std::string f;
      std::getline(fields, f, ',');
      x = std::stod(f);
    }
    rows.push_back({{v[0], v[1], v[2]}, {v[3], v[4], v[5]}, {v[6], v[7], v[8]}});
  }
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
  EXPECT_NEAR(std::hypot(changed.a, changed.b) / changed.L, std::hypot(lab.a, lab.b) / lab.L, 1e-12);
  EXPECT_DOUBLE_EQ(with_lightness(lab, 130.0).L, 100.0);
  EXPECT_DOUBLE_EQ(with_lightness(lab, -5.0).L, 0.0);
  Lab black{0.0, 0.0, 0.0};
  EXPECT_DOUBLE_EQ(with_lightness(black, 10.0).a, 0.0);  // k = 1 when L is ~0
}

}  // namespace
}  // namespace countershade
