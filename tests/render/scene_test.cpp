#include "render/scene.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "render/scene_loader.h"
#include "test_util.h"

namespace countershade {
namespace {

const char* kMinimal = R"({
  "version": 1,
  "camera": {"eye": [0, 0, 5], "target": [0, 0, 0], "width": 32, "height": 24},
  "objects": [{"name": "ball", "shape": {"type": "sphere", "radius": 1, "subdivisions": 2}}],
  "lights": [{"type": "directional", "direction": [0, 1, 1], "irradiance": 1}]
})";

// Replaces the first occurrence of `from` in the minimal scene.
std::string variant(const std::string& from, const std::string& to) {
  std::string text = kMinimal;
  auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  return text.replace(pos, from.size(), to);
}

TEST(Scene, LoadsMinimalSceneWithDefaults) {
  testing::TempDir dir;
  Scene scene = load_scene(testing::write_file(dir / "s.json", kMinimal));
  EXPECT_EQ(scene.camera.width, 32);
  EXPECT_EQ(scene.objects.size(), 1u);
  EXPECT_EQ(scene.objects[0].name, "ball");
  EXPECT_EQ(scene.objects[0].mesh.corner_normals.size(),
            3 * scene.objects[0].mesh.triangle_count());
  EXPECT_EQ(scene.objects[0].importance.size(), scene.objects[0].mesh.vertex_count());
  // The default is the noise budget: 0.5 L* RMS, p99 2, adaptive Sobol sampling.
  EXPECT_FALSE(scene.settings.spp.has_value());
  EXPECT_FALSE(scene.settings.fixed_vertex_spp().has_value());
  EXPECT_EQ(scene.settings.noise.target, 0.5);
  EXPECT_EQ(scene.settings.noise.p99, 2.0);
  EXPECT_EQ(scene.settings.sampling, SamplingMode::sobol);
  EXPECT_EQ(scene.display.encoding.kind(), DisplayEncoding::Kind::srgb);
  ASSERT_EQ(scene.directional_lights.size(), 1u);
  EXPECT_NEAR(scene.directional_lights[0].direction.y, std::sqrt(0.5), 1e-12);
}

// Every object's surface graph is built while the next objects are read; a plain render loads
// without them, and what needs them says so instead of reading an empty graph.
TEST(Scene, SurfaceGraphsAreBuiltOnRequest) {
  testing::TempDir dir;
  const std::string text = variant(
      R"("objects": [)",
      R"("objects": [{"name": "floor", "shape": {"type": "plane", "size": 4, "subdivisions": 30}},
                     {"name": "box", "shape": {"type": "box", "size": [1, 1, 1]}},)");
  const auto path = testing::write_file(dir / "s.json", text);
  const Scene with = load_scene(path);
  ASSERT_EQ(with.objects.size(), 3u);
  for (const Object& object : with.objects) {
    const SurfaceGraph expected = surface_graph(object.mesh.positions, object.mesh.triangles);
    EXPECT_EQ(object.surface.point_of, expected.point_of) << object.name;
    EXPECT_EQ(object.surface.adjacency.neighbours, expected.adjacency.neighbours) << object.name;
    EXPECT_EQ(object.surface.components.label, expected.components.label) << object.name;
  }
  EXPECT_NO_THROW(require_surface_graphs(with, "test"));

  const Scene without = load_scene(path, false);
  EXPECT_EQ(without.objects[0].surface.point_count(), 0u);
  EXPECT_THROW(require_surface_graphs(without, "test"), std::logic_error);
  EXPECT_EQ(without.objects[2].mesh.positions, with.objects[2].mesh.positions);
}

TEST(Scene, ReadsTheNoiseBudgetOrAFixedCount) {
  testing::TempDir dir;
  auto budget = load_scene(testing::write_file(
      dir / "budget.json", variant("\"version\": 1",
                                   "\"version\": 1, \"render\": {\"noise\": {\"target\": 0.3, "
                                   "\"min_spp\": 8, \"max_spp\": 512, \"time_limit\": 60}}")));
  EXPECT_FALSE(budget.settings.spp.has_value());
  EXPECT_EQ(budget.settings.noise.target, 0.3);
  EXPECT_EQ(budget.settings.noise.p99, 2.0);  // the default, at least 4 × the target
  EXPECT_EQ(budget.settings.noise.min_spp, 8);
  EXPECT_EQ(budget.settings.noise.max_spp, 512);
  EXPECT_EQ(budget.settings.noise.time_limit_s, 60.0);
  EXPECT_EQ(budget.settings.noise.allocation,
            NoiseAllocation::pixel);  // the default: every pixel meets the target
  auto over_image = load_scene(testing::write_file(
      dir / "image.json",
      variant("\"version\": 1",
              "\"version\": 1, \"render\": {\"noise\": {\"allocation\": \"image\"}}")));
  EXPECT_EQ(over_image.settings.noise.allocation, NoiseAllocation::image);
  auto fixed = load_scene(testing::write_file(
      dir / "fixed.json",
      variant("\"version\": 1",
              "\"version\": 1, \"render\": {\"spp\": 12, \"sampler\": \"independent\"}")));
  EXPECT_EQ(fixed.settings.spp, 12);
  EXPECT_EQ(fixed.settings.fixed_vertex_spp(), 3);  // a quarter, unless vertex_spp says otherwise
  EXPECT_EQ(fixed.settings.sampling, SamplingMode::independent);
  fixed.settings.spp = 4;
  EXPECT_EQ(fixed.settings.fixed_vertex_spp(), 2)
      << "one sample for each of the two replicates, at least";
}

TEST(Scene, RelativePathsResolveAgainstTheSceneFile) {
  testing::TempDir dir;
  std::filesystem::create_directories(dir / "meshes");
  testing::write_file(dir / "meshes/tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  auto scene_file = testing::write_file(
      dir / "s.json",
      variant(R"("shape": {"type": "sphere", "radius": 1, "subdivisions": 2})",
              R"("mesh": "meshes/tri.obj", "transform": {"translate": [0, 0, 1]})"));
  Scene scene = load_scene(scene_file);
  EXPECT_EQ(scene.objects[0].mesh.triangle_count(), 1u);
  EXPECT_FLOAT_EQ(scene.objects[0].mesh.positions[1].z, 1.0f);
}

// The objects' mesh files are loaded before the objects are read (on all cores, each file once):
// objects naming one file get meshes of their own, and the first object in order whose file
// cannot be loaded is the one named, as when they were loaded one by one.
TEST(Scene, MeshFilesLoadedAheadStayWithTheirObjects) {
  testing::TempDir dir;
  testing::write_file(dir / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  testing::write_file(dir / "quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  testing::write_file(dir / "noface.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  const std::string three = R"([{"mesh": "tri.obj"},
      {"mesh": "tri.obj", "transform": {"translate": [0, 0, 1]}}, {"mesh": "quad.obj"}])";
  const Scene scene = load_scene(testing::write_file(
      dir / "three.json",
      variant(R"([{"name": "ball", "shape": {"type": "sphere", "radius": 1, "subdivisions": 2}}])",
              three)));
  ASSERT_EQ(scene.objects.size(), 3u);
  EXPECT_EQ(scene.objects[0].mesh.triangles, scene.objects[1].mesh.triangles);
  EXPECT_FLOAT_EQ(scene.objects[0].mesh.positions[1].z, 0.0f);
  EXPECT_FLOAT_EQ(scene.objects[1].mesh.positions[1].z, 1.0f);
  EXPECT_EQ(scene.objects[2].mesh.triangle_count(), 2u);

  const std::string bad = R"([{"mesh": "tri.obj"}, {"mesh": "noface.obj"}, {"mesh": "none.obj"}])";
  const auto file = testing::write_file(
      dir / "bad.json",
      variant(R"([{"name": "ball", "shape": {"type": "sphere", "radius": 1, "subdivisions": 2}}])",
              bad));
  const std::string message = testing::input_error_of([&] { load_scene(file); });
  EXPECT_NE(
      message.find("objects[1].mesh: " + (dir / "noface.obj").string() + ": mesh has no faces"),
      std::string::npos)
      << message;
}

TEST(Scene, BadInputNamesFileAndKeyPath) {
  testing::TempDir dir;
  testing::write_file(dir / "nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
  testing::write_file(dir / "noface.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  struct Case {
    std::string text, expected;
  } cases[] = {
      {"{\"version\": 1,", "malformed JSON"},
      {variant("\"width\": 32", "\"width\": \"wide\""),
       "camera.width: expected an integer, got a string"},
      {variant("\"name\": \"ball\"", "\"name\": \"ball\", \"material\": {\"albdo\": 0.5}"),
       "objects[0].material.albdo: unknown key"},
      {variant("\"version\": 1", "\"version\": 7"), "version: unsupported scene format version 7"},
      {variant("\"eye\": [0, 0, 5]", "\"eye\": [0, 0]"),
       "camera.eye: expected an array of 3 numbers"},
      {variant("\"radius\": 1", "\"radius\": -1"), "objects[0].shape.radius: must be positive"},
      {variant("\"type\": \"sphere\"", "\"type\": \"torus\""),
       "objects[0].shape.type: unknown value 'torus'"},
      {variant("\"type\": \"sphere\", \"radius\": 1, \"subdivisions\": 2",
               "\"type\": \"disc\", \"segments\": 65536"),
       "objects[0].shape.segments: would make about 1367"},
      {variant("\"type\": \"sphere\", \"radius\": 1, \"subdivisions\": 2",
               "\"type\": \"cylinder\", \"segments\": 65536"),
       "objects[0].shape.segments: would make about"},
      {variant("\"type\": \"sphere\", \"radius\": 1, \"subdivisions\": 2",
               "\"type\": \"cylinder\", \"radius\": 1e-6, \"height\": 1000"),
       "objects[0].shape.height: would make about"},
      {variant("\"type\": \"sphere\", \"radius\": 1, \"subdivisions\": 2",
               "\"type\": \"disc\", \"height\": 1"),
       "objects[0].shape.height: unknown key"},
      {variant("\"type\": \"directional\"", "\"type\": \"spot\""),
       "lights[0].type: unknown value 'spot'"},
      {variant("\"irradiance\": 1", "\"irradiance\": -1"),
       "lights[0].irradiance: must not be negative"},
      {variant("\"shape\": {\"type\": \"sphere\", \"radius\": 1, \"subdivisions\": 2}",
               "\"mesh\": \"missing.obj\""),
       "objects[0].mesh: " + (dir / "missing.obj").string() + ": no such mesh file"},
      {variant("\"shape\": {\"type\": \"sphere\", \"radius\": 1, \"subdivisions\": 2}",
               "\"mesh\": \"nan.obj\""),
       "objects[0].mesh: " + (dir / "nan.obj").string() + ": line 2: vertex 1 has a NaN"},
      {variant("\"shape\": {\"type\": \"sphere\", \"radius\": 1, \"subdivisions\": 2}",
               "\"mesh\": \"noface.obj\""),
       "objects[0].mesh: " + (dir / "noface.obj").string() + ": mesh has no faces"},
      {variant("\"shape\": {\"type\": \"sphere\", \"radius\": 1, \"subdivisions\": 2}",
               "\"shape\": {\"type\": \"plane\"}, \"material\": {\"texture\": \"nope.png\"}"),
       "objects[0].material.texture: " + (dir / "nope.png").string() + ": no such image file"},
      {variant("\"name\": \"ball\"",
               "\"name\": \"ball\", \"material\": {\"texture\": \"nope.png\"}"),
       "objects[0].material.texture: the mesh has no texture coordinates"},
      {variant("\"shape\": {\"type\": \"sphere\", \"radius\": 1, \"subdivisions\": 2}",
               "\"shape\": {\"type\": \"plane\"}, \"material\": {\"texture\": {\"squares\": 3}}"),
       "objects[0].material.texture.squares: must be even and at most the size, so that the "
       "pattern tiles"},
      {variant("\"shape\": {\"type\": \"sphere\", \"radius\": 1, \"subdivisions\": 2}",
               "\"shape\": {\"type\": \"plane\"}, \"material\": {\"texture\": {\"pattern\": "
               "\"zigzag\"}}"),
       "objects[0].material.texture.pattern: unknown value 'zigzag'"},
      {variant("\"shape\": {\"type\": \"sphere\", \"radius\": 1, \"subdivisions\": 2}",
               "\"shape\": {\"type\": \"plane\"}, \"material\": {\"texture\": {\"pattern\": "
               "\"stripes\", \"stripes\": 3}}"),
       "objects[0].material.texture.stripes: must be even and at most the size, so that the "
       "pattern tiles"},
      {variant("\"shape\": {\"type\": \"sphere\", \"radius\": 1, \"subdivisions\": 2}",
               "\"shape\": {\"type\": \"plane\"}, \"material\": {\"texture\": {}, "
               "\"texture_encoding\": \"linear\"}"),
       "objects[0].material.texture_encoding: applies to texture image files only"},
      {variant("\"name\": \"ball\"", "\"name\": \"ball\", \"material\": {\"texture_repeat\": 4}"),
       "objects[0].material.texture_repeat: applies to a material with a texture only"},
      {variant("\"type\": \"directional\", \"direction\": [0, 1, 1], \"irradiance\": 1",
               "\"type\": \"environment\", \"file\": \"sky.exr\""),
       "lights[0].file: " + (dir / "sky.exr").string() + ": no such image file"},
      {variant("\"type\": \"directional\", \"direction\": [0, 1, 1], \"irradiance\": 1",
               "\"type\": \"environment\", \"constant\": 1, \"sampling\": \"specular\""),
       "lights[0].sampling: unknown value 'specular'"},
      {variant("\"objects\": [", "\"objects\": [], \"unused\": ["),
       "objects: a scene needs at least one object"},
      {variant("\"target\": [0, 0, 0]", "\"target\": [0, 0, 5]"),
       "camera.target: must differ from eye"},
      {variant("\"version\": 1", "\"version\": 1, \"render\": {\"spp\": 4, \"noise\": {}}"),
       "render.noise: give either a fixed spp or a noise budget, not both"},
      {variant("\"version\": 1", "\"version\": 1, \"render\": {\"spp\": 4, \"vertex_spp\": 1}"),
       "render.vertex_spp: must be in [2, 65536], got 1"},
      {variant("\"version\": 1", "\"version\": 1, \"render\": {\"noise\": {\"min_spp\": 5}}"),
       "render.noise.min_spp: must be even"},
      {variant("\"version\": 1", "\"version\": 1, \"render\": {\"noise\": {\"target\": 0}}"),
       "render.noise.target: "},
      {variant("\"version\": 1",
               "\"version\": 1, \"render\": {\"noise\": {\"min_spp\": 64, \"max_spp\": 32}}"),
       "render.noise.max_spp: "},
      {variant("\"version\": 1",
               "\"version\": 1, \"render\": {\"noise\": {\"allocation\": \"pixels\"}}"),
       "render.noise.allocation: expected \"pixel\" or \"image\""},
      {variant("\"version\": 1", "\"version\": 1, \"render\": {\"sampler\": \"independent\"}"),
       "render.sampler: the independent sampler takes a fixed spp"},
  };
  int i = 0;
  for (const auto& c : cases) {
    auto path = testing::write_file(dir / ("case" + std::to_string(i++) + ".json"), c.text);
    std::string message = testing::input_error_of([&] { load_scene(path); });
    EXPECT_EQ(message.rfind(path.string() + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(c.expected), std::string::npos)
        << "expected '" << c.expected << "' in: " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos);
  }
  EXPECT_NE(testing::input_error_of([&] { load_scene(dir / "absent.json"); }).find("no such file"),
            std::string::npos);
}

}  // namespace
}  // namespace countershade
