// Every method at absurd strengths: the stimulus saturates, but every pixel stays a number in
// [0, 1] and the noise model is a number or +inf. depth-usm multiplied float(1e300) = inf by a
// zero depth difference and wrote NaN pixels (a silent NaN flicker figure).

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "enhance/method.h"
#include "enhance/registry.h"
#include "enhance/view.h"
#include "enhance/view_plan.h"
#include "render/scene_loader.h"
#include "test_util.h"

namespace countershade {
namespace {

// A textured box on a textured floor under a shadowing light: depth steps, shadows, texture.
const char* kScene = R"({
  "version": 1,
  "camera": {"eye": [0, 2, 5], "target": [0, 0.3, 0], "width": 48, "height": 36},
  "render": {"spp": 2},
  "objects": [
    {"name": "floor", "shape": {"type": "plane", "size": 8, "subdivisions": 8},
     "material": {"texture": {"pattern": "checker-noise", "size": 64, "squares": 8, "noise": 0.3, "seed": 1}}},
    {"name": "box", "shape": {"type": "box", "size": [1, 1, 1], "subdivisions": 4},
     "transform": {"translate": [0, 0.5, 0]}, "material": {"albedo": 0.6}}
  ],
  "lights": [{"type": "directional", "direction": [1, 2, 1], "irradiance": 2}]
})";

// Parameters for every built-in method; the test fails for a method that is missing here.
const std::map<std::string, std::vector<nlohmann::json>>& parameters_of_every_method() {
  static const std::map<std::string, std::vector<nlohmann::json>> table = {
      {"none", {nlohmann::json::object()}},
      {"usm3d", {{{"sigma", 0.3}}}},
      {"usm2d", {{{"sigma_px", 2}}}},
      {"depth-usm",
       {{{"sigma_px", 2}, {"operator", "darken"}},
        {{"sigma_px", 2}, {"operator", "add"}},
        {{"sigma_px", 2}, {"operator", "color"}},
        {{"sigma_px", 2}, {"operator", "contrast"}},
        {{"sigma_px", 2}, {"operator", "add"}, {"space", "lab"}}}},
      {"cornsweet", {{{"sigma_px", 3}}, {{"mode", "surface"}, {"sigma", 0.2}}}},
      {"lla", {{{"sigma", 0.1}}}},
      {"exaggerated-shading", {{{"sigma", 0.1}}}},
      {"radiance-scaling", {nlohmann::json::object()}},
      {"light-warping", {nlohmann::json::object()}},
      {"texture-filter",
       {{{"mode", "post"}, {"filter", "unsharp"}},
        {{"mode", "mip"}, {"filter", "dog"}},
        {{"mode", "texture"}, {"filter", "bilateral"}}}},
  };
  return table;
}

TEST(ExtremeLambda, EveryMethodSaturatesToNumbersInRange) {
  testing::TempDir dir;
  auto scene =
      std::make_shared<const Scene>(load_scene(testing::write_file(dir / "s.json", kScene)));
  const auto& table = parameters_of_every_method();
  for (const std::string& name : method_names()) {
    ASSERT_TRUE(table.count(name)) << "no parameters for " << name << " in this test";
    for (const nlohmann::json& parameters : table.at(name)) {
      const auto view = render_view(scene, plan_for(name, parameters, 1e300), ViewOptions{});
      const auto prepared = prepare_method(name, view, parameters);
      for (double lambda : {1e300, -1e300, 1e38, -1e38, 1e6}) {
        const Composed out = prepared->compose(lambda);
        size_t bad = 0;
        for (float v : out.display.pixels) bad += !(v >= 0.0f && v <= 1.0f);
        EXPECT_EQ(bad, 0u) << name << " " << parameters.dump() << " at λ " << lambda;
        for (float s : prepared->noise(lambda).sigma) {
          if (std::isnan(s)) {
            ADD_FAILURE() << name << " " << parameters.dump() << ": NaN noise at λ " << lambda;
            break;
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace countershade
