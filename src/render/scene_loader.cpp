#include "render/scene_loader.h"

#include <tbb/task_group.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>
#include <sstream>
#include <stdexcept>
#include <string>

#include "core/atomic_file.h"
#include "core/color.h"
#include "core/display_calibration_file.h"
#include "core/error.h"
#include "core/image.h"
#include "core/json_reader.h"
#include "core/number_format.h"
#include "core/parallel.h"
#include "mesh/mesh_files.h"
#include "mesh/primitives.h"
#include "mesh/refine.h"
#include "render/procedural_texture.h"
#include "render/scene_animation.h"

namespace countershade {
namespace fs = std::filesystem;

namespace {

SurfaceGraph surface_of(const TriangleMesh& mesh) {
  return surface_graph(mesh.positions, mesh.triangles);
}

class SceneLoader {
 public:
  SceneLoader(const fs::path& path, bool surface_graphs)
      : path_(path), base_(path.parent_path()), surface_graphs_(surface_graphs) {}

  Scene load() {
    nlohmann::json json = parse_json_file(path_);
    JsonObject root(json, path_.string(), "");
    long long version = root.integer("version");
    if (version != kSceneFormatVersion)
      root.fail("version", "unsupported scene format version " + std::to_string(version) +
                               " (this build reads version " + std::to_string(kSceneFormatVersion) +
                               ")");
    Scene scene;
    scene.file = path_;
    scene.camera = camera(root.object("camera"));
    if (root.has("render")) scene.settings = settings(root.object("render"));
    if (root.has("display")) scene.display = display(root.object("display"));
    objects(root.objects("objects"), scene);
    if (scene.objects.empty()) root.fail("objects", "a scene needs at least one object");
    std::vector<LightRef> light_refs;
    if (root.has("lights"))
      for (const auto& l : root.objects("lights")) light_refs.push_back(light(l, scene));
    if (root.has("animation"))
      scene.animation = read_animation(root.object("animation"), scene, light_refs);
    if (root.has("description")) root.string("description");
    root.finish();
    return scene;
  }

 private:
  fs::path resolve(const JsonObject& o, const std::string& key) const {
    fs::path p = o.string(key);
    if (p.empty()) o.fail(key, "empty path");
    return p.is_absolute() ? p : base_ / p;
  }

  // The mesh files the objects name (where "mesh" is a path at all: object() reports the rest).
  std::vector<fs::path> mesh_files(const std::vector<JsonObject>& list) const {
    std::vector<fs::path> files;
    for (const JsonObject& o : list) {
      if (!o.has("mesh") || !o.raw("mesh").is_string()) continue;
      const fs::path p = o.raw("mesh").get<std::string>();
      if (!p.empty()) files.push_back(p.is_absolute() ? p : base_ / p);
    }
    return files;
  }

  // Reads the objects, their mesh files loaded on all cores first. Each one's surface graph (when
  // asked for) is built on another core while the next objects are read.
  void objects(const std::vector<JsonObject>& list, Scene& scene) {
    meshes_ = MeshFiles(mesh_files(list));
    scene.objects.reserve(list.size());  // the builds hold on to the meshes
    std::vector<SurfaceGraph> graphs(list.size());
    tbb::task_group builds;
    try {
      for (size_t i = 0; i < list.size(); ++i) {
        scene.objects.push_back(object(list[i]));
        const TriangleMesh* mesh = &scene.objects.back().mesh;
        if (surface_graphs_) builds.run([&graphs, i, mesh] { graphs[i] = surface_of(*mesh); });
      }
    } catch (...) {
      builds.wait();
      throw;
    }
    builds.wait();
    if (surface_graphs_)
      for (size_t i = 0; i < list.size(); ++i) scene.objects[i].surface = std::move(graphs[i]);
  }

  static double positive(const JsonObject& o, const std::string& key, double fallback) {
    double v = o.number_or(key, fallback);
    if (!(v > 0)) o.fail(key, "must be positive");
    return v;
  }

  static glm::dvec3 non_negative_color(const JsonObject& o, const std::string& key,
                                       const glm::dvec3& fallback) {
    glm::dvec3 c = o.vec3_or(key, fallback);
    if (c.x < 0 || c.y < 0 || c.z < 0) o.fail(key, "must not be negative");
    return c;
  }

  static glm::dvec3 unit_vector(const JsonObject& o, const std::string& key) {
    glm::dvec3 d = o.vec3(key);
    if (glm::length(d) < 1e-12) o.fail(key, "must not be the zero vector");
    return glm::normalize(d);
  }

  Camera camera(const JsonObject& o) {
    Camera c;
    c.eye = o.vec3("eye");
    c.target = o.vec3("target");
    c.up = o.vec3_or("up", {0, 1, 0});
    if (glm::length(c.target - c.eye) < 1e-12) o.fail("target", "must differ from eye");
    if (glm::length(glm::cross(c.target - c.eye, c.up)) < 1e-9)
      o.fail("up", "must not be parallel to the viewing direction");
    std::string projection = o.choice("projection", "perspective", {"perspective", "orthographic"});
    c.orthographic = projection == "orthographic";
    if (c.orthographic) {
      c.ortho_height = positive(o, "height_world", 2.0);
    } else {
      c.vertical_fov_deg = o.number_in("fov", 40.0, 1e-3, 179.0);
    }
    c.width = int(o.integer_in("width", 640, 1, 16384));
    c.height = int(o.integer_in("height", 480, 1, 16384));
    o.finish();
    return c;
  }

  RenderSettings settings(const JsonObject& o) {
    RenderSettings s;
    if (o.has("spp") && o.has("noise"))
      o.fail("noise", "give either a fixed spp or a noise budget, not both");
    if (o.has("spp")) s.spp = int(o.integer_in("spp", 16, 1, 65536));
    if (o.has("vertex_spp")) s.vertex_spp = int(o.integer_in("vertex_spp", 4, 2, 65536));
    if (o.has("noise")) s.noise = read_noise_budget(o.object("noise"));
    s.sampling = o.choice("sampler", "sobol", {"sobol", "independent"}) == "sobol"
                     ? SamplingMode::sobol
                     : SamplingMode::independent;
    if (s.sampling == SamplingMode::independent && !s.spp)
      o.fail("sampler",
             "the independent sampler takes a fixed spp (the noise budget samples adaptively with "
             "sobol)");
    s.seed = uint64_t(o.integer_in("seed", 1, 0, (1ll << 53)));
    o.finish();
    return s;
  }

  Display display(const JsonObject& o) {
    Display d;
    d.exposure_stops = o.number_in("exposure", 0.0, -30.0, 30.0);
    d.black_level = o.number_in("black_level", 0.0, 0.0, 0.5);
    if (o.has("calibration")) {
      if (o.has("encoding") || o.has("lut") || o.has("gamma"))
        o.fail("calibration",
               "a calibrated display takes its encoding from the calibration; give no encoding, "
               "lut or gamma");
      calibrated(o, resolve(o, "calibration"), d);
      if (o.has("background")) d.background = non_negative_color(o, "background", glm::dvec3(0));
      o.finish();
      return d;
    }
    std::string encoding = o.choice("encoding", "srgb", {"srgb", "gamma", "lut"});
    if (encoding == "gamma") {
      d.encoding = DisplayEncoding::gamma(o.number_in("gamma", 2.2, 0.1, 10.0));
    } else if (encoding == "lut") {
      d.encoding = read_lut_file(o, "lut", resolve(o, "lut"));
    }
    if (o.has("background")) d.background = non_negative_color(o, "background", glm::dvec3(0));
    o.finish();
    return d;
  }

  // The display block that `countershade calibrate` wrote (core/display_calibration_file.h).
  static void calibrated(const JsonObject& o, const fs::path& file, Display& d) {
    std::error_code ec;
    if (!fs::is_regular_file(file, ec))
      o.fail("calibration", "no such file '" + file.string() + "'");
    const CalibratedDisplay c = read_calibration_file(file);
    d.encoding = c.encoding;
    d.luminance_cd_m2 = std::make_pair(c.black_cd_m2, c.white_cd_m2);
  }

  glm::dmat4 transform(const JsonObject& o) {
    if (o.has("matrix")) {
      std::vector<double> m = o.numbers("matrix");
      if (m.size() != 16) o.fail("matrix", "expected 16 numbers (row-major 4x4)");
      glm::dmat4 t;
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) t[c][r] = m[size_t(r * 4 + c)];
      // A singular linear part collapses the object to a plane, line or point (no normals).
      if (!(std::abs(glm::determinant(glm::dmat3(t))) > 1e-12))
        o.fail("matrix",
               "is singular (the determinant of its 3x3 part is 0): the object would have no "
               "volume or area");
      o.finish();
      return t;
    }
    glm::dvec3 scale(1.0);
    if (o.has("scale")) {
      scale = o.vec3("scale");
      if (scale.x == 0 || scale.y == 0 || scale.z == 0) o.fail("scale", "must not be zero");
    }
    glm::dvec3 rotate = o.vec3_or("rotate", glm::dvec3(0));
    glm::dvec3 translate = o.vec3_or("translate", glm::dvec3(0));
    o.finish();
    // Scale, then rotate about x, y, z (degrees), then translate.
    glm::dmat4 t = glm::translate(glm::dmat4(1.0), translate);
    t = glm::rotate(t, glm::radians(rotate.z), glm::dvec3(0, 0, 1));
    t = glm::rotate(t, glm::radians(rotate.y), glm::dvec3(0, 1, 0));
    t = glm::rotate(t, glm::radians(rotate.x), glm::dvec3(1, 0, 0));
    return glm::scale(t, scale);
  }

  // A primitive's triangles are counted before it is built: a box of 4096 subdivisions would have
  // 2e8 of them. The fuzz build keeps inputs small enough to finish within its time limit under
  // the sanitizers.
#ifdef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
  static constexpr double kMaxPrimitiveTriangles = 2e5;
#else
  static constexpr double kMaxPrimitiveTriangles = 5e7;
#endif
  static void check_triangles(const JsonObject& o, double triangles,
                              const std::string& key = "subdivisions") {
    if (triangles > kMaxPrimitiveTriangles)
      o.fail(key, "would make about " + std::to_string(std::llround(triangles)) +
                      " triangles (the limit is " +
                      std::to_string(std::llround(kMaxPrimitiveTriangles)) + ")");
  }

  // A plane, or a relief: the plane displaced by coarse and fine relief whose heights are
  // fractions of its size.
  static TriangleMesh plane(const JsonObject& o, bool relief) {
    const int subdivisions = int(o.integer_in("subdivisions", relief ? 256 : 32, 1, 4096));
    check_triangles(o, 2.0 * subdivisions * subdivisions);
    const double size = positive(o, "size", 1.0);
    if (!relief) return make_plane(size, subdivisions);
    const double coarse = o.number_in("coarse", 0.1, -1.0, 1.0),
                 fine = o.number_in("fine", 0.004, -1.0, 1.0);
    return make_relief(size, subdivisions, coarse * size, fine * size);
  }

  // A cylinder, or a disc (a cylinder's cap on its own), refused before it is built when it would
  // have too many triangles.
  static TriangleMesh round_shape(const JsonObject& o, bool disc) {
    const double radius = positive(o, "radius", 0.5),
                 height = disc ? 0.0 : positive(o, "height", 1.0);
    const int segments = int(o.integer_in("segments", 64, 3, 65536));
    const double triangles = round_grid(radius, height, segments).triangle_bound(disc);
    // The height (for its radius) is to blame when even the fewest segments are too many.
    const bool height_to_blame =
        !disc && round_grid(radius, height, 3).triangle_bound(disc) > kMaxPrimitiveTriangles;
    check_triangles(o, triangles, height_to_blame ? "height" : "segments");
    return disc ? make_disc(radius, segments) : make_cylinder(radius, height, segments);
  }

  TriangleMesh shape(const JsonObject& o) {
    std::string type =
        o.choice("type", "", {"plane", "relief", "box", "sphere", "cylinder", "disc"});
    TriangleMesh mesh;
    if (type == "plane" || type == "relief") {
      mesh = plane(o, type == "relief");
    } else if (type == "box") {
      glm::dvec3 size = o.vec3_or("size", glm::dvec3(1.0));
      if (size.x <= 0 || size.y <= 0 || size.z <= 0) o.fail("size", "must be positive");
      if (o.has("bevel") && o.has("chamfer"))
        o.fail("chamfer", "give either bevel or chamfer, not both");
      EdgeProfile profile = o.has("bevel")     ? EdgeProfile::bevel
                            : o.has("chamfer") ? EdgeProfile::chamfer
                                               : EdgeProfile::sharp;
      double radius = 0;
      if (profile != EdgeProfile::sharp) {
        std::string key = profile == EdgeProfile::bevel ? "bevel" : "chamfer";
        radius = o.number(key);
        if (!(radius > 0) || radius >= 0.5 * std::min({size.x, size.y, size.z}))
          o.fail(key, "must be positive and less than half the smallest side");
      }
      const int segments = int(o.integer_in("edge_segments", 4, 1, 256)),
                subdivisions = int(o.integer_in("subdivisions", 32, 1, 4096));
      check_triangles(o, 12.0 * (subdivisions + segments) * (subdivisions + segments));
      mesh = make_box(size, profile, radius, segments, subdivisions);
    } else if (type == "sphere") {
      mesh = make_sphere(positive(o, "radius", 1.0), int(o.integer_in("subdivisions", 4, 0, 8)));
    } else {
      mesh = round_shape(o, type == "disc");
    }
    o.finish();
    return mesh;
  }

  std::shared_ptr<const Texture> texture(const JsonObject& o, const std::string& key,
                                         bool srgb_encoded) {
    fs::path file = resolve(o, key);
    std::string cache_key = file.string() + (srgb_encoded ? "#srgb" : "#linear");
    for (const auto& [k, t] : textures_)
      if (k == cache_key) return t;
    Image image;
    try {
      image = read_image(file);
      check_finite(file, image);  // radiance and albedo: no infinity either
    } catch (const InputError& e) {
      o.fail(key, e.what());
    }
    auto tex = std::make_shared<const Texture>(level_from_image(image, srgb_encoded));
    textures_.emplace_back(cache_key, tex);
    return tex;
  }

  std::shared_ptr<const Texture> procedural_texture(const JsonObject& o) {
    if (o.choice("pattern", "checker-noise", {"checker-noise", "stripes"}) == "stripes")
      return stripe_texture(o);
    CheckerNoise spec;
    spec.size = int(o.integer_in("size", 1024, 8, 8192));
    spec.squares = int(o.integer_in("squares", 16, 2, 1024));
    if (spec.squares % 2 != 0 || spec.squares > spec.size)
      o.fail("squares", "must be even and at most the size, so that the pattern tiles");
    spec.noise = o.number_in("noise", 0.35, 0.0, 1.0);
    spec.seed = uint64_t(o.integer_in("seed", 1, 0, (1ll << 53)));
    o.finish();
    return std::make_shared<const Texture>(checker_noise(spec));
  }

  std::shared_ptr<const Texture> stripe_texture(const JsonObject& o) {
    Stripes spec;
    spec.size = int(o.integer_in("size", 1024, 8, 8192));
    spec.stripes = int(o.integer_in("stripes", 16, 2, 1024));
    if (spec.stripes % 2 != 0 || spec.stripes > spec.size)
      o.fail("stripes", "must be even and at most the size, so that the pattern tiles");
    spec.light = o.number_in("light", 0.6, 0.0, 1.0);
    spec.dark = o.number_in("dark", 0.15, 0.0, 1.0);
    o.finish();
    return std::make_shared<const Texture>(stripes(spec));
  }

  Material material(const JsonObject& o) {
    Material m;
    m.albedo = non_negative_color(o, "albedo", m.albedo);
    if (m.albedo.x > 1 || m.albedo.y > 1 || m.albedo.z > 1) o.fail("albedo", "must be at most 1");
    std::string encoding = o.choice("texture_encoding", "srgb", {"srgb", "linear"});
    if (o.has("texture") && o.raw("texture").is_object()) {
      if (o.has("texture_encoding"))
        o.fail("texture_encoding", "applies to texture image files only");
      m.texture = procedural_texture(o.object("texture"));
    } else if (o.has("texture")) {
      m.texture = texture(o, "texture", encoding == "srgb");
    }
    if (o.has("texture_repeat") && !m.texture)
      o.fail("texture_repeat", "applies to a material with a texture only");
    m.texture_repeat = o.number_in("texture_repeat", 1.0, 1e-3, 1e4);
    if (o.has("specular")) {
      JsonObject s = o.object("specular");
      std::string model = s.choice("model", "", {"blinn-phong", "cook-torrance"});
      if (model == "blinn-phong") {
        m.specular = SpecularModel::blinn_phong;
        m.specular_color = non_negative_color(s, "color", glm::dvec3(0.04));
        m.shininess = s.number_in("shininess", 64.0, 1.0, 100000.0);
      } else {
        m.specular = SpecularModel::cook_torrance;
        m.specular_color = non_negative_color(s, "f0", glm::dvec3(0.04));
        m.roughness = s.number_in("roughness", 0.3, 0.02, 1.0);
      }
      s.finish();
    }
    o.finish();
    return m;
  }

  std::vector<float> importance(const JsonObject& o, const std::string& key,
                                const TriangleMesh& mesh) {
    const nlohmann::json& value = o.raw(key);
    if (value.is_number()) return std::vector<float>(mesh.vertex_count(), float(o.number(key)));
    JsonObject w = o.object(key);
    std::string channel = w.choice("vertex_color", "", {"r", "g", "b", "luminance"});
    std::vector<double> range = w.has("range") ? w.numbers("range") : std::vector<double>{0.0, 1.0};
    if (range.size() != 2) w.fail("range", "expected [low, high]");
    w.finish();
    if (!mesh.has_vertex_colors())
      o.fail(key, "the mesh has no vertex colours to read weights from");
    std::vector<float> weights(mesh.vertex_count());
    for (size_t v = 0; v < weights.size(); ++v) {
      const glm::vec3& c = mesh.vertex_colors[v];
      double t = channel == "r"   ? c.r
                 : channel == "g" ? c.g
                 : channel == "b" ? c.b
                                  : 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
      weights[v] = float(range[0] + t * (range[1] - range[0]));
    }
    return weights;
  }

  Object object(const JsonObject& o) {
    Object obj;
    obj.name = o.string_or("name", "object" + std::to_string(object_count_++));
    bool has_mesh = o.has("mesh"), has_shape = o.has("shape");
    if (has_mesh == has_shape) o.fail("", "an object needs exactly one of 'mesh' or 'shape'");
    double crease = 180.0;
    if (has_mesh) {
      fs::path file = resolve(o, "mesh");
      try {
        obj.mesh = meshes_.take(file);
      } catch (const InputError& e) {
        o.fail("mesh", e.what());
      }
      if (o.boolean_or("fit", false)) fit_to_unit(obj.mesh);
    } else {
      obj.mesh = shape(o.object("shape"));
      crease = 30.0;  // primitives have true creases (box edges, cylinder rims)
    }
    crease = o.number_in("crease_angle", crease, 0.0, 180.0);
    if (obj.mesh.has_uvs() == false && o.has("material") && o.raw("material").contains("texture"))
      o.fail("material.texture", "the mesh has no texture coordinates");
    obj.material = o.has("material") ? material(o.object("material")) : Material{};
    obj.importance = o.has("importance") ? importance(o, "importance", obj.mesh)
                                         : std::vector<float>(obj.mesh.vertex_count(), 1.0f);
    compute_corner_normals(obj.mesh, crease);
    if (o.has("transform")) transform_mesh(obj.mesh, transform(o.object("transform")));
    check_world_positions(o, obj.mesh);
    o.finish();
    return obj;
  }

  // Transformed positions must stay finite and within ±1e15 (a translation of 1e88 overflows float,
  // and the renderer's welding and ray tracing need room for their own arithmetic).
  static void check_world_positions(const JsonObject& o, const TriangleMesh& mesh) {
    constexpr float kLimit = 1e15f;
    for (const glm::vec3& p : mesh.positions)
      if (!(std::abs(p.x) <= kLimit && std::abs(p.y) <= kLimit && std::abs(p.z) <= kLimit))
        o.fail("transform",
               "puts vertices outside ±1e15 (or makes them not finite); scenes are in metres");
  }

  // Centres the mesh on the origin in x and z, stands it on y = 0 and scales its largest extent
  // to 1.
  static void fit_to_unit(TriangleMesh& mesh) {
    BoundingBox box = bounding_box(mesh);
    glm::vec3 extent = box.hi - box.lo;
    float s = 1.0f / std::max({extent.x, extent.y, extent.z});
    glm::vec3 centre = 0.5f * (box.lo + box.hi);
    for (auto& p : mesh.positions) p = (p - glm::vec3(centre.x, box.lo.y, centre.z)) * s;
  }

  // Adds the light to the scene; returns where it went (for the animation's references).
  LightRef light(const JsonObject& o, Scene& scene) {
    const size_t directional = scene.directional_lights.size(), point = scene.point_lights.size();
    add_light(o, scene);
    if (scene.directional_lights.size() > directional)
      return {LightRef::Kind::directional, directional};
    if (scene.point_lights.size() > point) return {LightRef::Kind::point, point};
    return {};
  }

  void add_light(const JsonObject& o, Scene& scene) {
    const std::string type =
        o.choice("type", "", {"directional", "point", "environment", "ambient"});
    if (type == "directional")
      add_directional(o, scene);
    else if (type == "point")
      add_point(o, scene);
    else if (type == "environment")
      add_environment(o, scene);
    else
      add_ambient(o, scene);
    o.finish();
  }

  static void add_directional(const JsonObject& o, Scene& scene) {
    DirectionalLight l;
    l.direction = unit_vector(o, "direction");
    l.irradiance = non_negative_color(o, "irradiance", l.irradiance);
    l.angular_radius_deg = o.number_in("angular_radius", 0.0, 0.0, 45.0);
    l.samples = int(o.integer_in("samples", l.angular_radius_deg > 0 ? 4 : 1, 1, 4096));
    l.shadows = o.boolean_or("shadows", true);
    scene.directional_lights.push_back(l);
  }

  static void add_point(const JsonObject& o, Scene& scene) {
    PointLight l;
    l.position = o.vec3("position");
    l.intensity = non_negative_color(o, "intensity", l.intensity);
    l.radius = o.number_in("radius", 0.0, 0.0, 1e9);
    l.samples = int(o.integer_in("samples", l.radius > 0 ? 4 : 1, 1, 4096));
    scene.point_lights.push_back(l);
  }

  void add_environment(const JsonObject& o, Scene& scene) const {
    if (scene.environment) o.fail("type", "a scene can have only one environment light");
    EnvironmentLight l;
    const int sources = int(o.has("file")) + int(o.has("sky")) + int(o.has("constant"));
    if (sources != 1) o.fail("", "an environment needs exactly one of 'file', 'sky' or 'constant'");
    l.map = environment_map(o);
    l.scale = o.number_in("scale", 1.0, 0.0, 1e9);
    const std::string sampling =
        o.choice("sampling", "importance", {"importance", "cosine", "cosine+specular"});
    l.sampling = sampling == "importance" ? EnvironmentSampling::importance
                 : sampling == "cosine"   ? EnvironmentSampling::cosine
                                          : EnvironmentSampling::cosine_and_specular;
    l.samples = int(o.integer_in("samples", 4, 1, 4096));
    l.visible_to_camera = o.boolean_or("visible", true);
    scene.environment = l;
  }

  // The environment's radiance: an image file (display-encoded formats decoded to linear), the
  // procedural sky, or a constant.
  std::shared_ptr<EnvironmentMap> environment_map(const JsonObject& o) const {
    if (o.has("file")) {
      const fs::path file = resolve(o, "file");
      Image image;
      try {
        image = read_image(file);
        check_finite(file, image);
      } catch (const InputError& e) {
        o.fail("file", e.what());
      }
      const std::string ext = lower_extension(file);
      if (ext == ".png" || ext == ".jpg" || ext == ".jpeg")
        for (float& v : image.pixels) v = float(srgb_decode(v));
      return std::make_shared<EnvironmentMap>(image);
    }
    if (o.has("sky")) {
      JsonObject s = o.object("sky");
      SkyParameters sky;
      sky.zenith = non_negative_color(s, "zenith", sky.zenith);
      sky.horizon = non_negative_color(s, "horizon", sky.horizon);
      sky.ground = non_negative_color(s, "ground", sky.ground);
      s.finish();
      return std::make_shared<EnvironmentMap>(EnvironmentMap::sky(sky));
    }
    return std::make_shared<EnvironmentMap>(
        EnvironmentMap::constant(non_negative_color(o, "constant", glm::dvec3(1.0))));
  }

  static void add_ambient(const JsonObject& o, Scene& scene) {
    scene.ambient.radiance = non_negative_color(o, "radiance", glm::dvec3(0.1));
    scene.ambient.distance = o.number_in("occlusion_distance", 0.0, 0.0, 1e9);
    scene.ambient.samples = int(o.integer_in("samples", 4, 1, 4096));
  }

  fs::path path_, base_;
  bool surface_graphs_;
  int object_count_ = 0;
  MeshFiles meshes_;
  std::vector<std::pair<std::string, std::shared_ptr<const Texture>>> textures_;
};

}  // namespace

Scene load_scene(const fs::path& path, bool surface_graphs) {
  return SceneLoader(path, surface_graphs).load();
}

NoiseBudget read_noise_budget(const JsonObject& o) {
  NoiseBudget b;
  b.target = o.number_in("target", b.target, 0.01, 100.0);
  b.p99 = o.number_in("p99", std::max(b.p99, 4 * b.target), b.target, 1000.0);
  b.min_spp = int(o.integer_in("min_spp", b.min_spp, 2, 65536));
  b.max_spp = int(o.integer_in("max_spp", b.max_spp, b.min_spp, 65536));
  if (b.min_spp % 2) o.fail("min_spp", "must be even (the samples form two replicates)");
  b.time_limit_s = o.number_in("time_limit", 0.0, 0.0, 1e7);
  const std::string allocation = o.string_or("allocation", "pixel");
  if (allocation != "pixel" && allocation != "image")
    o.fail("allocation", "expected \"pixel\" or \"image\"");
  b.allocation = allocation == "image" ? NoiseAllocation::image : NoiseAllocation::pixel;
  o.finish();
  return b;
}

}  // namespace countershade
