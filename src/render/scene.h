#pragma once
// Scene description: camera, objects with materials, lights, display. Loaded from a versioned
// JSON file (docs/scene-format.md); every error names the file and the key path.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/display.h"
#include "core/sampler.h"
#include "mesh/surface_graph.h"
#include "mesh/triangle_mesh.h"
#include "render/animation.h"
#include "render/camera.h"
#include "render/environment.h"
#include "render/texture.h"

namespace countershade {

inline constexpr int kSceneFormatVersion = 1;

enum class SpecularModel { none, blinn_phong, cook_torrance };

struct Material {
  glm::dvec3 albedo{0.8};                  // diffuse reflectance (used when there is no texture)
  std::shared_ptr<const Texture> texture;  // diffuse reflectance from the mesh UVs
  double texture_repeat = 1;               // the texture tiles this many times across the UV square
  SpecularModel specular = SpecularModel::none;
  glm::dvec3 specular_color{0.04};  // Blinn–Phong ks, or Cook–Torrance F0
  double shininess = 64.0;          // Blinn–Phong exponent
  double roughness = 0.3;           // Cook–Torrance GGX roughness (alpha = roughness²)
};

struct Object {
  std::string name;
  TriangleMesh mesh;  // world space, corner normals filled
  Material material;
  std::vector<float> importance;  // per-vertex weight for 3D unsharp masking (default 1)
  SurfaceGraph surface;  // welded points and their 1-ring (load_scene, refinement); may be left out
};

struct DirectionalLight {
  glm::dvec3 direction{0, 1, 0};  // unit, pointing from the scene towards the light
  glm::dvec3 irradiance{1.0};     // on a surface facing the light
  double angular_radius_deg = 0;  // 0 = hard shadows
  int samples = 1;                // shadow rays per shading sample for soft shadows
  bool shadows = true;            // false: no shadow rays, only the attached shading (n·l)
};

struct PointLight {
  glm::dvec3 position{0, 5, 0};
  glm::dvec3 intensity{10.0};  // radiant intensity; irradiance falls off as 1/r²
  double radius = 0;           // 0 = hard shadows; >0 = spherical light, soft shadows
  int samples = 1;
};

// How an environment's directions are drawn: in proportion to the map's radiance, cosine-weighted
// over the hemisphere, or cosine-weighted mixed with the material's specular lobe (a quarter of
// the samples, render/specular_lobe.h).
enum class EnvironmentSampling { importance, cosine, cosine_and_specular };

struct EnvironmentLight {
  std::shared_ptr<const EnvironmentMap> map;
  double scale = 1.0;
  EnvironmentSampling sampling = EnvironmentSampling::importance;
  int samples = 4;                // rays per shading sample
  bool visible_to_camera = true;  // camera rays that miss see the environment
};

// Ambient light of constant radiance, attenuated by ambient occlusion within `distance`.
struct AmbientLight {
  glm::dvec3 radiance{0.0};
  double distance = 0;  // 0 disables occlusion (plain ambient term)
  int samples = 4;
};

struct Display {
  double exposure_stops = 0;
  double black_level = 0;  // share of full scale shown at radiance 0 (Exposure::black)
  DisplayEncoding encoding = DisplayEncoding::srgb();
  std::optional<glm::dvec3> background;  // linear radiance where camera rays miss; overrides env
  // A photometer-calibrated display (`calibration`, docs/display.md): the luminance of code 0
  // and of full scale, in cd/m².
  std::optional<std::pair<double, double>> luminance_cd_m2;

  Exposure exposure() const { return {std::exp2(exposure_stops), black_level}; }
};

// How many samples an image takes. By default a noise budget: every pixel is sampled until the
// standard error of its L* meets the target (see render/pixel_pass.h). A fixed count is there for
// those who want one.
// Where the noise budget's target applies: at every pixel, or to the image's RMS (pixel_pass.cpp,
// stopping_threshold).
enum class NoiseAllocation { pixel, image };

struct NoiseBudget {
  double target = 0.5;  // RMS sampling noise of the written image, in L*
  NoiseAllocation allocation = NoiseAllocation::pixel;
  double p99 = 2.0;  // the 99th percentile of its per-pixel error, in L*
  int min_spp = 16, max_spp = 4096;
  double time_limit_s = 0;  // 0: none. When it stops the sampling the image is not reproducible.
};

struct RenderSettings {
  std::optional<int> spp;         // a fixed count per pixel instead of the budget
  std::optional<int> vertex_spp;  // a fixed count per vertex instead of the budget
  NoiseBudget noise;
  SamplingMode sampling = SamplingMode::sobol;
  uint64_t seed = 1;

  // The fixed count per vertex: vertex_spp, or with a fixed spp a quarter of it (the smoothing
  // averages many vertices) and at least 2 (one per replicate); none under the budget.
  std::optional<int> fixed_vertex_spp() const {
    if (vertex_spp) return vertex_spp;
    if (spp) return std::max(2, *spp / 4);
    return std::nullopt;
  }
};

struct Scene {
  std::filesystem::path file;
  Camera camera;
  std::vector<Object> objects;
  std::vector<DirectionalLight> directional_lights;
  std::vector<PointLight> point_lights;
  std::optional<EnvironmentLight> environment;
  AmbientLight ambient;
  Display display;
  RenderSettings settings;
  std::optional<Animation>
      animation;  // moving stimuli: scene_at (render/scene_animation.h) poses it

  BoundingBox bounds() const;
};

// Builds (or rebuilds, after the meshes changed) every object's surface graph, objects side by
// side.
void build_surface_graphs(Scene& scene, int threads = 0);

// Throws std::logic_error unless every object has its surface graph (`who` names the caller).
void require_surface_graphs(const Scene& scene, const char* who);

// Splits every edge longer than `max_edge_length` (tessellation refinement before surface
// smoothing). Returns the number of splits.
size_t refine_scene(Scene& scene, double max_edge_length);

}  // namespace countershade
