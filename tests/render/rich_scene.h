#pragma once
// A small scene that exercises every shading path: every kind of light, soft shadows, ambient
// occlusion, a repeated texture, a glossy material and adaptive sampling.

#include <memory>
#include <string>

#include "render/scene.h"
#include "render/scene_loader.h"
#include "test_util.h"

namespace countershade::testing {

inline constexpr const char* kRichScene = R"({
  "version": 1,
  "camera": {"eye": [2.2, 1.8, 3.0], "target": [0, 0.4, 0], "fov": 40, "width": 48, "height": 36},
  "render": {"seed": 3, "noise": {"target": 1.0, "min_spp": 4, "max_spp": 64}},
  "objects": [
    {"name": "floor", "shape": {"type": "plane", "size": 4, "subdivisions": 4},
     "material": {"albedo": 0.6, "texture": {"size": 64, "squares": 8}, "texture_repeat": 2}},
    {"name": "ball", "shape": {"type": "sphere", "radius": 0.5, "subdivisions": 3}, "transform": {"translate": [-0.4, 0.5, 0]},
     "material": {"albedo": [0.7, 0.5, 0.4], "specular": {"model": "blinn-phong", "color": 0.2, "shininess": 40}}},
    {"name": "box", "shape": {"type": "box", "size": [0.6, 0.9, 0.6]}, "transform": {"translate": [0.6, 0.45, -0.3]}}
  ],
  "lights": [
    {"type": "directional", "direction": [0.5, 0.8, 0.3], "irradiance": 1.5, "angular_radius": 4, "samples": 2},
    {"type": "point", "position": [-1.5, 2.0, 1.5], "intensity": 3, "radius": 0.3, "samples": 2},
    {"type": "environment", "sky": {}, "samples": 2, "scale": 0.4},
    {"type": "ambient", "radiance": 0.05, "occlusion_distance": 0.6, "samples": 2}
  ]
})";

inline std::shared_ptr<const Scene> rich_scene(const TempDir& dir) {
  return std::make_shared<const Scene>(load_scene(write_file(dir / "rich.json", kRichScene)));
}

// The same scene at a fixed count of 6 samples per pixel instead of the noise budget.
inline std::shared_ptr<const Scene> fixed_count_scene(const TempDir& dir) {
  std::string json = kRichScene;
  const std::string budget = R"("noise": {"target": 1.0, "min_spp": 4, "max_spp": 64})";
  json.replace(json.find(budget), budget.size(), R"("spp": 6)");
  return std::make_shared<const Scene>(load_scene(write_file(dir / "fixed.json", json)));
}

}  // namespace countershade::testing
