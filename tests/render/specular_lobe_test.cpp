// Environment light drawn from both the cosine and the material's specular lobe: the lobe's
// density is that of the directions it draws, and a render with the mixture has the expected
// image of cosine sampling alone, with less noise on glossy surfaces.

#include "render/specular_lobe.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <iostream>
#include <numbers>

#include "core/random.h"
#include "render/renderer.h"
#include "render/scene_loader.h"
#include "render/shading.h"
#include "test_util.h"

namespace countershade {
namespace {

// ∫ pdf dω over the cone of half-angle `angle` around `axis`, by midpoint quadrature.
double pdf_in_cone(const Material& m, const glm::dvec3& n, const glm::dvec3& wo,
                   const glm::dvec3& axis, double angle) {
  const int steps = 600;
  const TangentFrame frame(axis);
  double sum = 0;
  for (int i = 0; i < steps; ++i) {
    const double theta = (i + 0.5) / steps * angle;
    for (int j = 0; j < steps; ++j) {
      const glm::dvec3 wi = direction_around(frame, std::cos(theta), (j + 0.5) / steps);
      sum += specular_lobe_pdf(m, n, wo, wi) * std::sin(theta);
    }
  }
  return sum * (angle / steps) * (2 * std::numbers::pi / steps);
}

Material glossy(SpecularModel model) {
  Material m;
  m.specular = model;
  m.roughness = 0.35;
  m.shininess = 80;
  return m;
}

TEST(SpecularLobe, ItsDensityIsThatOfTheDirectionsItDraws) {
  const glm::dvec3 n(0, 0, 1), wo = glm::normalize(glm::dvec3(std::sin(0.7), 0, std::cos(0.7)));
  const glm::dvec3 mirror = 2.0 * glm::dot(wo, n) * n - wo;
  for (SpecularModel model : {SpecularModel::cook_torrance, SpecularModel::blinn_phong}) {
    const Material m = glossy(model);
    // Cones around the mirror direction and around a direction off it.
    const glm::dvec3 off = glm::normalize(mirror + glm::dvec3(0, 0.25, 0));
    const struct {
      glm::dvec3 axis;
      double angle;
    } cones[] = {{mirror, 0.1}, {mirror, 0.3}, {off, 0.15}};
    const int n_samples = 400000;
    int inside[3] = {0, 0, 0};
    SampleStream random(11, 0, 0, 0);
    for (int i = 0; i < n_samples; ++i) {
      const double u1 = random.next(), u2 = random.next();
      const std::optional<glm::dvec3> wi = sample_specular_lobe(m, TangentFrame(n), wo, u1, u2);
      if (!wi) continue;
      ASSERT_NEAR(glm::length(*wi), 1.0, 1e-12);
      ASSERT_GT(specular_lobe_pdf(m, n, wo, *wi), 0.0);
      for (int c = 0; c < 3; ++c)
        inside[c] +=
            std::acos(std::clamp(glm::dot(*wi, cones[c].axis), -1.0, 1.0)) < cones[c].angle;
    }
    for (int c = 0; c < 3; ++c) {
      const double expected = pdf_in_cone(m, n, wo, cones[c].axis, cones[c].angle);
      const double share = double(inside[c]) / n_samples,
                   sd = std::sqrt(expected * (1 - expected) / n_samples);
      EXPECT_GT(expected, 0.01) << "cone " << c;
      EXPECT_NEAR(share, expected, 4 * sd + 1e-3 * expected)
          << "model " << int(model) << " cone " << c;
    }
  }
}

TEST(SpecularLobe, NoDirectionWhereTheHalfVectorFacesAwayFromTheViewer) {
  const Material m = glossy(SpecularModel::cook_torrance);
  const glm::dvec3 n(0, 0, 1), grazing = glm::normalize(glm::dvec3(1, 0, 0.01));
  EXPECT_EQ(specular_lobe_pdf(m, n, grazing, -grazing), 0.0);
  EXPECT_FALSE(has_specular_lobe(Material{}));
  EXPECT_TRUE(has_specular_lobe(m));
}

// A glossy sphere under a sky: the mixture's image has cosine sampling's mean, with less noise.
Scene glossy_sphere(const testing::TempDir& dir, const std::string& sampling, int spp) {
  return load_scene(testing::write_file(dir / (sampling + ".json"), R"({
    "version": 1,
    "camera": {"eye": [0, 0.6, 4], "target": [0, 0, 0], "fov": 30, "width": 20, "height": 20},
    "render": {"spp": )" + std::to_string(spp) + R"(, "seed": 5},
    "objects": [{"shape": {"type": "sphere", "radius": 1, "subdivisions": 5},
                 "material": {"albedo": 0.5, "specular": {"model": "cook-torrance", "f0": 0.05, "roughness": 0.5}}}],
    "lights": [{"type": "environment", "sky": {}, "samples": 4, "sampling": ")" +
                                                                        sampling +
                                                                        R"(", "visible": false}],
    "display": {"background": 0.2}
  })"));
}

double mean_green(const RenderResult& r) {
  double sum = 0;
  for (int y = 0; y < r.radiance.height; ++y)
    for (int x = 0; x < r.radiance.width; ++x) sum += r.radiance.at(x, y, 1);
  return sum / (r.radiance.width * r.radiance.height);
}

double rms(const std::vector<float>& v) {
  double sum = 0;
  for (float x : v) sum += double(x) * x;
  return std::sqrt(sum / double(v.size()));
}

TEST(SpecularLobe, MixedEnvironmentSamplingKeepsTheMeanAndCutsTheNoise) {
  testing::TempDir dir;
  // At 4096 samples the image means of three seeds spread by 0.03 % with either sampling; a wrong
  // density in the mixture moves the mean by far more.
  const Scene cosine = glossy_sphere(dir, "cosine", 4096),
              mixed = glossy_sphere(dir, "cosine+specular", 4096);
  const RenderResult a = render(cosine, RayTracer(cosine)), b = render(mixed, RayTracer(mixed));
  const double mean_a = mean_green(a), mean_b = mean_green(b);
  EXPECT_NEAR(mean_b, mean_a, 0.001 * mean_a);
  std::cout << "noise RMS " << rms(a.noise) << " (cosine) and " << rms(b.noise) << " (mixed)\n";
  EXPECT_LT(rms(b.noise), 0.5 * rms(a.noise));
}

}  // namespace
}  // namespace countershade
