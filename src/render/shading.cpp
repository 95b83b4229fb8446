#include "render/shading.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "core/fast_math.h"
#include "render/specular_lobe.h"

namespace countershade {
namespace {

constexpr double kPi = std::numbers::pi;

// Light samples per shading point: a delta light needs one, an area light its `samples`.
int samples_per_point(const DirectionalLight& light) {
  return light.angular_radius_deg > 0 ? light.samples : 1;
}
int samples_per_point(const PointLight& light) { return light.radius > 0 ? light.samples : 1; }

// The points of up to kDirectionLanes samples of one light, drawn side by side (the lanes past the
// last sample hold 0), and the directions drawn from them.
struct PointLanes {
  PointLanes(const Sampler::Block& block, int first, int count) {
    block.points(first, count, u1, u2);
  }
  double u1[kDirectionLanes] = {}, u2[kDirectionLanes] = {};
};
static_assert(kDirectionLanes == Sampler::kBlockLanes);
struct DirectionLanes {
  double x[kDirectionLanes], y[kDirectionLanes], z[kDirectionLanes];
  glm::dvec3 operator[](int i) const { return {x[i], y[i], z[i]}; }
};

}  // namespace

SurfacePoint surface_point(const Scene& scene, unsigned object, unsigned triangle, double b1,
                           double b2) {
  const TriangleMesh& mesh = scene.objects[object].mesh;
  const glm::uvec3& tri = mesh.triangles[triangle];
  double b0 = 1.0 - b1 - b2;
  glm::dvec3 p0 = mesh.positions[tri.x], p1 = mesh.positions[tri.y], p2 = mesh.positions[tri.z];
  SurfacePoint sp;
  sp.object = object;
  sp.triangle = triangle;
  sp.b1 = b1;
  sp.b2 = b2;
  sp.position = b0 * p0 + b1 * p1 + b2 * p2;
  sp.geometric_normal = glm::normalize(glm::cross(p1 - p0, p2 - p0));
  size_t c = 3 * size_t(triangle);
  glm::dvec3 n = b0 * glm::dvec3(mesh.corner_normals[c]) +
                 b1 * glm::dvec3(mesh.corner_normals[c + 1]) +
                 b2 * glm::dvec3(mesh.corner_normals[c + 2]);
  double len = glm::length(n);
  sp.shading_normal = len > 1e-12 ? n / len : sp.geometric_normal;
  if (mesh.has_uvs())
    sp.uv = b0 * glm::dvec2(mesh.corner_uvs[c]) + b1 * glm::dvec2(mesh.corner_uvs[c + 1]) +
            b2 * glm::dvec2(mesh.corner_uvs[c + 2]);
  return sp;
}

glm::dvec3 Shader::albedo(const SurfacePoint& point) const {
  const Material& m = scene_.objects[point.object].material;
  const Texture* texture = texture_hook_ ? texture_hook_->texture(point.object, m) : nullptr;
  if (!texture) texture = m.texture.get();
  if (!texture) return m.albedo;
  const double repeat = m.texture_repeat;
  return texture->sample(point.uv * repeat, point.duv_dx * repeat, point.duv_dy * repeat);
}

glm::dvec3 Shader::background(const glm::dvec3& direction) const {
  if (scene_.display.background) return *scene_.display.background;
  if (scene_.environment && scene_.environment->visible_to_camera)
    return scene_.environment->scale * scene_.environment->map->radiance(direction);
  return glm::dvec3(0.0);
}

glm::dvec3 specular_brdf(const ShadingInputs& s, const glm::dvec3& wi) {
  const Material& m = s.material;
  const glm::dvec3& n = s.normal;
  double n_wi = glm::dot(n, wi), n_wo = std::max(glm::dot(n, s.wo), 1e-4);
  if (m.specular == SpecularModel::none || n_wi <= 0) return glm::dvec3(0.0);
  glm::dvec3 h = glm::normalize(wi + s.wo);
  double n_h = std::max(glm::dot(n, h), 0.0);
  if (m.specular == SpecularModel::blinn_phong)  // energy-normalised Blinn–Phong lobe
    return m.specular_color * ((m.shininess + 8.0) / (8.0 * kPi)) * std::pow(n_h, m.shininess);
  // Cook–Torrance: GGX distribution, separable Smith masking, Schlick Fresnel.
  const double a2 = ggx_alpha2(m), D = ggx_distribution(a2, n_h);
  auto g1 = [a2](double c) { return 2.0 * c / (c + std::sqrt(a2 + (1.0 - a2) * c * c)); };
  double G = g1(n_wi) * g1(n_wo);
  double w_h = std::max(glm::dot(s.wo, h), 0.0);
  glm::dvec3 F = m.specular_color + (glm::dvec3(1.0) - m.specular_color) * std::pow(1.0 - w_h, 5.0);
  return F * (D * G / (4.0 * n_wi * n_wo));
}

glm::dvec3 brdf(const ShadingInputs& s, const glm::dvec3& wi) {
  return s.albedo / kPi + specular_brdf(s, wi);
}

glm::dvec3 reflect_diffuse(const ShadingInputs& s, const glm::dvec3& wi,
                           const glm::dvec3& incident) {
  double cos_i = glm::dot(s.normal, wi);
  return cos_i > 0 ? s.albedo / kPi * incident * cos_i : glm::dvec3(0.0);
}

glm::dvec3 reflect_specular(const ShadingInputs& s, const glm::dvec3& wi,
                            const glm::dvec3& incident) {
  double cos_i = glm::dot(s.normal, wi);
  return cos_i > 0 ? specular_brdf(s, wi) * incident * cos_i : glm::dvec3(0.0);
}

glm::dvec3 reflect_plain(const ShadingInputs& s, const glm::dvec3& wi, const glm::dvec3& incident) {
  double cos_i = glm::dot(s.normal, wi);
  return cos_i > 0 ? brdf(s, wi) * incident * cos_i : glm::dvec3(0.0);
}

glm::dvec3 shadow_origin(const Scene& scene, const SurfacePoint& p, bool back) {
  const TriangleMesh& mesh = scene.objects[p.object].mesh;
  const glm::uvec3& tri = mesh.triangles[p.triangle];
  const size_t c = 3 * size_t(p.triangle);
  const double b[3] = {1.0 - p.b1 - p.b2, p.b1, p.b2};
  const unsigned v[3] = {tri.x, tri.y, tri.z};
  glm::dvec3 lift(0.0);
  for (int k = 0; k < 3; ++k) {
    const glm::dvec3 n =
        back ? -glm::dvec3(mesh.corner_normals[c + k]) : glm::dvec3(mesh.corner_normals[c + k]);
    const double below = glm::dot(p.position - glm::dvec3(mesh.positions[v[k]]), n);
    if (below < 0) lift -= b[k] * below * n;
  }
  return p.position + lift;
}

// The shadow rays of one shading point, asked while its light samples are drawn and answered
// together once all are: traced in Embree packets (faster than one by one), or read from the
// replayed answers. Each answer goes to its sample's `arrives`, or to the ambient count. Its
// arrays keep their size from point to point; the first `count` entries are the point's.
struct Shader::ShadowQueue {
  std::vector<ShadowRay> rays;
  std::vector<LightSampleRecord*> samples;  // whose `arrives` each ray answers; null: ambient
  std::vector<uint8_t> blocked;
  size_t count = 0;
  // Room for `most` rays, none asked yet.
  void start(size_t most) {
    if (rays.size() < most) {
      rays.resize(most);
      samples.resize(most);
      blocked.resize(most);
    }
    count = 0;
  }
  // The next ray's entry, to be filled in (field by field: cheaper than copying a whole ray).
  ShadowRay& ask(LightSampleRecord* sample) {
    samples[count] = sample;
    return rays[count++];
  }
};

struct Shader::Context {
  const SurfacePoint& point;
  glm::dvec3 normal, ng;             // shading and geometric normal on the viewed side
  glm::dvec3 origin;                 // where its shadow rays start (shadow_origin)
  ShadowAnswers* answers = nullptr;  // recorded or replayed shadow answers
  LightSampleRecord* lights;         // the next light sample to draw
  glm::dvec3 wo{0.0};                // towards the viewer (the specular lobe's samples need it)
  ShadowQueue* queue = nullptr;      // where gather() asks its shadow rays
};

size_t Shader::count_light_samples(const Scene& scene) {
  size_t n = 0;
  for (const auto& light : scene.directional_lights) n += size_t(samples_per_point(light));
  for (const auto& light : scene.point_lights) n += size_t(samples_per_point(light));
  if (scene.environment) n += size_t(scene.environment->samples);
  return n;
}

void Shader::shadow_ray(const Context& c, const glm::dvec3& wi, double distance,
                        ShadowRay& ray) const {
  const double eps = tracer_.epsilon();
  // Leave the surface on the side the ray travels to, so the surface does not shadow itself.
  ray.origin = c.origin + c.ng * (glm::dot(c.ng, wi) >= 0 ? eps : -eps);
  ray.direction = wi;
  ray.tnear = eps;
  ray.tfar = distance - 2 * eps;
}

bool Shader::visible(const Context& c, const glm::dvec3& wi, double distance,
                     RayCounts& counts) const {
  ++counts.shadow;
  ShadowRay ray;
  shadow_ray(c, wi, distance, ray);
  return !tracer_.occluded(ray.origin, ray.direction, ray.tnear, ray.tfar);
}

void Shader::answer_shadows(ShadowQueue& q, ShadowAnswers* answers, RayCounts& counts) const {
  const size_t n = q.count;
  if (answers && answers->replay) {
    if (size_t(answers->replay_end - answers->replay) < n)
      throw std::logic_error("Shader: a replayed sample asks more shadow rays than it recorded");
    for (size_t i = 0; i < n; ++i) q.blocked[i] = *answers->replay++ == 0;
  } else {
    counts.shadow += n;
    tracer_.occluded(std::span(q.rays.data(), n), q.blocked.data());
    if (answers && answers->record)
      for (size_t i = 0; i < n; ++i) answers->record->push_back(!q.blocked[i]);
  }
  for (size_t i = 0; i < n; ++i)
    if (q.samples[i]) q.samples[i]->arrives = !q.blocked[i];
}

LightSampleRecord& Shader::draw(Context& c, const glm::dvec3& wi, const glm::dvec3& radiance,
                                double divisor, double distance) const {
  // Light from behind the shading normal never arrives, with or without hooks, so a render with
  // hooks asks exactly the shadow rays of the render without them.
  LightSampleRecord& light = *c.lights++;
  const bool facing = glm::dot(c.normal, wi) > 0;
  // Field by field: a whole record built and copied costs more (its parts are stored and
  // reloaded in pieces of other sizes).
  light.wi = wi;
  light.radiance = radiance;
  light.divisor = divisor;
  light.arrives = facing;
  // Whether it arrives is answered with the point's other rays.
  if (facing && distance > 0) shadow_ray(c, wi, distance, c.queue->ask(&light));
  return light;
}

double terminator_fade(double cos_i, double band) {
  if (band <= 0 || cos_i >= band) return cos_i > 0 ? 1.0 : 0.0;
  const double x = std::max(cos_i, 0.0) / band;
  return x * x * (3 - 2 * x);
}

glm::dvec3 Shader::reflect(const ShadingInputs& s, const LightSampleRecord& light,
                           const glm::dvec3*& given) const {
  const double cos_i = glm::dot(s.normal, light.wi);
  if (!shading_hook_) return brdf(s, light.wi) * light.radiance * (cos_i / light.divisor);
  const glm::dvec3 incident = light.radiance / light.divisor;
  const glm::dvec3 hooked = given ? *given++ : shading_hook_->reflect(s, light.wi, incident);
  const double band = shading_hook_->terminator_band();
  if (band <= 0) return hooked;
  const double fade = terminator_fade(cos_i, band);
  if (fade >= 1) return hooked;
  // Near the original light's terminator the hook's change fades out, so the hooked shading meets
  // the plain one (zero at the terminator) continuously along the smooth shading normal.
  const glm::dvec3 plain = reflect_plain(s, light.wi, incident);
  return plain + fade * (hooked - plain);
}

std::vector<TangentFrame> Shader::light_frames(const Scene& scene) {
  std::vector<TangentFrame> frames;
  for (const auto& light : scene.directional_lights) frames.emplace_back(light.direction);
  return frames;
}

std::vector<Shader::DarkSideRay> Shader::dark_side_rays(const Scene& scene) {
  std::vector<DarkSideRay> rays;
  for (const auto& light : scene.directional_lights)
    rays.insert(rays.end(), size_t(samples_per_point(light)),
                light.shadows ? DarkSideRay::to_infinity : DarkSideRay::none);
  for (const auto& light : scene.point_lights)
    rays.insert(rays.end(), size_t(samples_per_point(light)), DarkSideRay::to_point);
  // An environment's samples from behind the normal are never shaded: its cosine sampler draws
  // none there, and an importance-sampled one would need a ray per sample and per λ.
  if (scene.environment)
    rays.insert(rays.end(), size_t(scene.environment->samples), DarkSideRay::never);
  return rays;
}

Shader::DarkSide Shader::dark_side(const ShadingInputs& s, const LightSampleRecord& light,
                                   size_t k) const {
  // Only a sample from behind the shading normal: one that faces it and does not arrive is a cast
  // shadow. A sample with nothing to carry (inside a point light) needs nothing.
  if (!shading_hook_ || !shading_hook_->shades_dark_side() ||
      shading_hook_->terminator_band() > 0 || glm::dot(s.normal, light.wi) > 0 ||
      light.radiance == glm::dvec3(0.0) || dark_side_rays_[k] == DarkSideRay::never)
    return DarkSide::dark;
  return dark_side_rays_[k] == DarkSideRay::none ? DarkSide::unshadowed : DarkSide::traced;
}

bool Shader::dark_side_open(const ShadingInputs& s, const ShadingRecord& r,
                            const LightSampleRecord& light, size_t k,
                            const std::optional<glm::dvec3>& towards) const {
  if (!towards || !(glm::dot(s.normal, *towards) > 0)) return false;
  // Another object (or another part of this one) may still block the direction it is shaded with.
  // A point light's divisor is the squared distance to the sampled point on it.
  const double reach =
      dark_side_rays_[k] == DarkSideRay::to_point ? std::sqrt(light.divisor) : 1e30;
  const Context c{
      s.point, s.normal, r.geometric_normal(s.point), shadow_origin(scene_, s.point, r.back),
      nullptr, nullptr};
  RayCounts counts;
  return visible(c, *towards, reach, counts);
}

void Shader::directional(Context& c, Sampler& random) const {
  const TangentFrame* frame = light_frames_.data();
  for (const auto& light : scene_.directional_lights) {
    const double cos_max = std::cos(glm::radians(light.angular_radius_deg));
    const int samples = samples_per_point(light);
    const Sampler::Block block = random.next2d_block(samples);
    for (int first = 0; first < samples; first += kDirectionLanes) {
      const int count = std::min(kDirectionLanes, samples - first);
      const PointLanes u(block, first, count);
      DirectionLanes cone;
      if (light.angular_radius_deg > 0)
        sample_cone_lanes(*frame, cos_max, u.u1, u.u2, cone.x, cone.y, cone.z);
      for (int i = 0; i < count; ++i) {
        const glm::dvec3 wi = light.angular_radius_deg > 0 ? cone[i] : light.direction;
        // Without shadows the light reaches every point that faces it (distance 0: no shadow
        // ray).
        draw(c, wi, light.irradiance, 1.0, light.shadows ? 1e30 : 0.0);
      }
    }
    ++frame;
  }
}

void Shader::point_lights(Context& c, Sampler& random) const {
  for (const auto& light : scene_.point_lights) {
    const int samples = samples_per_point(light);
    const Sampler::Block block = random.next2d_block(samples);
    for (int s = 0; s < samples; ++s) {
      const glm::dvec2 u = block.point(s);
      glm::dvec3 target = light.position;
      if (light.radius > 0) {  // uniform point on the spherical light
        double z = 1.0 - 2.0 * u.x, r = std::sqrt(std::max(0.0, 1.0 - z * z)), sin_phi, cos_phi;
        sincos_turns(u.y, sin_phi, cos_phi);
        target += light.radius * glm::dvec3(r * cos_phi, r * sin_phi, z);
      }
      glm::dvec3 to_light = target - c.point.position;
      double d2 = glm::dot(to_light, to_light);
      if (d2 <= 0) {
        *c.lights++ = LightSampleRecord{};  // inside the light: nothing arrives
        continue;
      }
      double d = std::sqrt(d2);
      draw(c, to_light / d, light.intensity, d2, d);
    }
  }
}

void Shader::environment(Context& c, Sampler& random) const {
  if (!scene_.environment) return;
  const EnvironmentLight& env = *scene_.environment;
  if (env.sampling == EnvironmentSampling::importance) return environment_from_map(c, random);
  const Material& material = scene_.objects[c.point.object].material;
  const TangentFrame frame(c.normal);  // shared by the samples drawn around the normal
  // With cosine+specular, the last quarter of the samples (at least one) come from the lobe.
  const bool mixed =
      env.sampling == EnvironmentSampling::cosine_and_specular && has_specular_lobe(material);
  const int from_lobe = mixed ? std::max(1, env.samples / 4) : 0,
            by_cosine = env.samples - from_lobe;
  // Each strategy's samples are one block of points, so that a pixel's samples stratify each
  // strategy's directions on their own. The points and cosine directions are drawn eight at a
  // time, side by side in vector lanes.
  const Sampler::Block cosine_block = random.next2d_block(by_cosine);
  for (int first = 0; first < by_cosine; first += kDirectionLanes) {
    const int count = std::min(kDirectionLanes, by_cosine - first);
    const PointLanes u(cosine_block, first, count);
    DirectionLanes cosine;
    sample_cosine_hemisphere_lanes(frame, u.u1, u.u2, cosine.x, cosine.y, cosine.z);
    for (int i = 0; i < count; ++i) environment_sample(c, material, cosine[i], from_lobe);
  }
  if (from_lobe == 0) return;
  const Sampler::Block lobe_block = random.next2d_block(from_lobe);
  for (int s = 0; s < from_lobe; ++s) {
    const glm::dvec2 u = lobe_block.point(s);
    environment_sample(c, material, sample_specular_lobe(material, frame, c.wo, u.x, u.y),
                       from_lobe);
  }
}

void Shader::environment_sample(Context& c, const Material& material,
                                const std::optional<glm::dvec3>& drawn, int from_lobe) const {
  const EnvironmentLight& env = *scene_.environment;
  const double pdf = drawn ? mixture_pdf(c, material, *drawn, env.samples, from_lobe) : 0.0;
  if (pdf <= 0) {
    *c.lights++ = LightSampleRecord{};
    return;
  }
  draw(c, *drawn, glm::dvec3(0.0), pdf, 1e30);  // its sky's radiance comes with the answers
}

void Shader::sky_radiance(LightSampleRecord* lights) const {
  const EnvironmentLight* env = scene_.environment ? &*scene_.environment : nullptr;
  if (!env || env->sampling == EnvironmentSampling::importance) return;
  // Looked up only for the samples that arrive: evaluate() reads no other (an environment's
  // samples are never lit on the dark side), and the lookup costs an acos.
  LightSampleRecord* first = lights + (light_samples_ - size_t(env->samples));
  for (LightSampleRecord* light = first; light != first + env->samples; ++light)
    if (light->arrives) light->radiance = env->map->radiance(light->wi);
}

void Shader::environment_from_map(Context& c, Sampler& random) const {
  const EnvironmentLight& env = *scene_.environment;
  // Two blocks: the texel's choice and column, then its row (the second number unused), so that
  // a pixel's samples stratify the choice of texel over all of them.
  const Sampler::Block texel = random.next2d_block(env.samples),
                       row = random.next2d_block(env.samples);
  for (int s = 0; s < env.samples; ++s) {
    const glm::dvec2 u = texel.point(s);
    const auto sample = env.map->sample(u.x, u.y, row.point(s).x);
    if (sample.pdf <= 0) {
      *c.lights++ = LightSampleRecord{};
      continue;
    }
    draw(c, sample.direction, sample.radiance, sample.pdf, 1e30);
  }
}

double Shader::mixture_pdf(const Context& c, const Material& material, const glm::dvec3& wi,
                           int samples, int from_lobe) {
  // The balance heuristic over all the samples: each one divided by the share-weighted density of
  // both strategies (the cosine's alone without a lobe).
  const double cosine = std::max(glm::dot(c.normal, wi), 0.0) / kPi;
  if (from_lobe == 0) return cosine;
  const double lobe = specular_lobe_pdf(material, c.normal, c.wo, wi);
  return ((samples - from_lobe) * cosine + from_lobe * lobe) / samples;
}

bool Shader::ambient_rays(Context& c, Sampler& random) const {
  const AmbientLight& ambient = scene_.ambient;
  if (ambient.radiance == glm::dvec3(0.0) || ambient.distance <= 0) return false;
  const TangentFrame frame(c.normal);
  const Sampler::Block block = random.next2d_block(ambient.samples);
  for (int s = 0; s < ambient.samples; ++s) {
    const glm::dvec2 u = block.point(s);
    shadow_ray(c, sample_cosine_hemisphere(frame, u.x, u.y), ambient.distance,
               c.queue->ask(nullptr));
  }
  return true;
}

double Shader::ambient_open(const ShadowQueue& q, size_t first, size_t end) const {
  int unoccluded = 0;
  for (size_t i = first; i < end; ++i) unoccluded += !q.samples[i] && !q.blocked[i];
  return double(unoccluded) / scene_.ambient.samples;
}

size_t Shader::most_shadow_rays() const {
  return light_samples_ + size_t(std::max(scene_.ambient.samples, 0));
}

bool Shader::draw_samples(const SurfacePoint& point, const glm::dvec3& wo, bool two_sided,
                          Sampler& random, ShadowAnswers* answers, ShadowQueue& queue,
                          ShadingRecord& record, LightSampleRecord* lights) const {
  record.duv_dx = point.duv_dx;
  record.duv_dy = point.duv_dy;
  record.wo = wo;
  record.back = two_sided && glm::dot(point.geometric_normal, wo) < 0;
  record.albedo = albedo(point);
  Context c{point,
            record.shading_normal(point),
            record.geometric_normal(point),
            shadow_origin(scene_, point, record.back),
            answers,
            lights,
            wo,
            &queue};
  directional(c, random);
  point_lights(c, random);
  environment(c, random);
  return ambient_rays(c, random);
}

void Shader::finish_point(const ShadowQueue& queue, size_t first, size_t end, bool ambient,
                          ShadingRecord& record, LightSampleRecord* lights) const {
  sky_radiance(lights);
  record.ambient_open = ambient ? ambient_open(queue, first, end) : 1.0;
}

void Shader::gather(const SurfacePoint& point, const glm::dvec3& wo, bool two_sided,
                    Sampler& random, RayCounts& counts, ShadowAnswers* answers,
                    ShadingRecord& record, LightSampleRecord* lights) const {
  thread_local ShadowQueue queue;
  queue.start(most_shadow_rays());
  const bool ambient = draw_samples(point, wo, two_sided, random, answers, queue, record, lights);
  answer_shadows(queue, answers, counts);
  finish_point(queue, 0, queue.count, ambient, record, lights);
}

void Shader::radiance_many(std::span<const PointToShade> points, RayCounts& counts,
                           glm::dvec3* radiance) const {
  thread_local ShadowQueue queue;
  thread_local std::vector<ShadingRecord> records;
  thread_local std::vector<LightSampleRecord> lights;  // light_samples_ per point
  thread_local std::vector<size_t> first_ray;          // each point's first ray, and the end
  thread_local std::vector<uint8_t> ambient;
  const size_t n = points.size(), per_point = light_samples_;
  queue.start(n * most_shadow_rays());
  records.resize(n);
  lights.resize(n * per_point);  // before drawing: the queue points into it
  first_ray.resize(n + 1);
  ambient.resize(n);
  for (size_t k = 0; k < n; ++k) {
    first_ray[k] = queue.count;
    ambient[k] = draw_samples(*points[k].point, points[k].wo, true, *points[k].random, nullptr,
                              queue, records[k], &lights[k * per_point]);
  }
  first_ray[n] = queue.count;
  answer_shadows(queue, nullptr, counts);
  for (size_t k = 0; k < n; ++k) {
    LightSampleRecord* own = &lights[k * per_point];
    finish_point(queue, first_ray[k], first_ray[k + 1], ambient[k] != 0, records[k], own);
    radiance[k] = evaluate(*points[k].point, records[k], own, records[k].albedo);
  }
}

glm::dvec3 Shader::evaluate(const SurfacePoint& point, const ShadingRecord& r,
                            const LightSampleRecord* lights, const glm::dvec3& albedo) const {
  const glm::dvec3* hooked = nullptr;
  return evaluate_inputs(inputs(point, r, albedo), r, lights, hooked);
}

void Shader::replay_many(std::span<const ReplayInput> records, glm::dvec3* radiance) const {
  thread_local std::vector<ShadingInputs> points;
  thread_local std::vector<HookSample> samples;
  thread_local std::vector<glm::dvec3> hooked;
  thread_local std::vector<uint8_t> lit;
  points.clear();
  points.reserve(records.size());  // `samples` points into it: no reallocation below
  for (const ReplayInput& in : records)
    points.push_back(
        inputs(*in.point, *in.record, texture_hook_ ? albedo(*in.point) : in.record->albedo));
  lit_samples(records, points, lit);
  // The samples evaluate_inputs reflects through `hooked`, in order: every lit one.
  samples.clear();
  for (size_t j = 0; shading_hook_ && j < records.size(); ++j)
    for (size_t k = 0; k < light_samples_; ++k)
      if (lit[j * light_samples_ + k]) {
        const LightSampleRecord& light = records[j].lights[k];
        samples.push_back({&points[j], light.wi, light.radiance / light.divisor});
      }
  hooked.resize(samples.size());
  if (shading_hook_) shading_hook_->reflect_many(samples, hooked.data());
  const glm::dvec3* next = shading_hook_ ? hooked.data() : nullptr;
  for (size_t j = 0; j < records.size(); ++j)
    radiance[j] = evaluate_inputs(points[j], *records[j].record, records[j].lights, next,
                                  &lit[j * light_samples_]);
}

void Shader::lit_samples(std::span<const ReplayInput> records,
                         std::span<const ShadingInputs> points, std::vector<uint8_t>& lit) const {
  thread_local std::vector<HookSample> traced;
  thread_local std::vector<size_t> where;  // each traced sample's index in `lit`
  thread_local std::vector<std::optional<glm::dvec3>> towards;
  traced.clear();
  where.clear();
  lit.assign(records.size() * light_samples_, 0);
  for (size_t j = 0; j < records.size(); ++j)
    for (size_t k = 0; k < light_samples_; ++k) {
      const LightSampleRecord& light = records[j].lights[k];
      const DarkSide side = light.arrives ? DarkSide::unshadowed : dark_side(points[j], light, k);
      lit[j * light_samples_ + k] = side == DarkSide::unshadowed;
      if (side != DarkSide::traced) continue;
      traced.push_back({&points[j], light.wi, light.radiance / light.divisor});
      where.push_back(j * light_samples_ + k);
    }
  // The rays of the dark side, their directions asked of the hook all at once.
  towards.assign(traced.size(), std::nullopt);
  if (!traced.empty()) shading_hook_->dark_side_directions(traced, towards.data());
  for (size_t t = 0; t < traced.size(); ++t) {
    const size_t j = where[t] / light_samples_, k = where[t] % light_samples_;
    lit[where[t]] =
        dark_side_open(points[j], *records[j].record, records[j].lights[k], k, towards[t]);
  }
}

bool Shader::sample_lit(const ShadingInputs& s, const ShadingRecord& r,
                        const LightSampleRecord& light, size_t k) const {
  if (light.arrives) return true;
  switch (dark_side(s, light, k)) {
    case DarkSide::unshadowed:
      return true;
    case DarkSide::traced:
      return dark_side_open(s, r, light, k, shading_hook_->dark_side_direction(s, light.wi));
    default:
      return false;
  }
}

glm::dvec3 Shader::evaluate_inputs(const ShadingInputs& s, const ShadingRecord& r,
                                   const LightSampleRecord* lights, const glm::dvec3*& hooked,
                                   const uint8_t* lit) const {
  const glm::dvec3& albedo = s.albedo;
  // Sums per light, in the order the samples were drawn. A sample that does not arrive adds
  // nothing, unless it lies on the original light's dark side and the hook lights it there
  // (sample_lit).
  size_t k = 0;
  auto sum_of = [&](int samples) {
    glm::dvec3 sum(0.0);
    for (int j = 0; j < samples; ++j, ++k)
      if (lit ? lit[k] != 0 : sample_lit(s, r, lights[k], k)) sum += reflect(s, lights[k], hooked);
    return sum;
  };
  glm::dvec3 L(0.0);
  auto add_mean = [&](int samples) { L += sum_of(samples) / double(samples); };
  for (const auto& light : scene_.directional_lights) add_mean(samples_per_point(light));
  for (const auto& light : scene_.point_lights) add_mean(samples_per_point(light));
  if (const auto& env = scene_.environment)
    L += env->scale * sum_of(env->samples) / double(env->samples);
  if (scene_.ambient.radiance != glm::dvec3(0.0))
    L += albedo * scene_.ambient.radiance * r.ambient_open;
  return L;
}

glm::dvec3 Shader::radiance(const SurfacePoint& point, const glm::dvec3& wo, bool two_sided,
                            Sampler& random, RayCounts& counts, ShadowAnswers* answers) const {
  thread_local std::vector<LightSampleRecord> lights;
  lights.resize(light_samples_);
  ShadingRecord record;
  gather(point, wo, two_sided, random, counts, answers, record, lights.data());
  return evaluate(point, record, lights.data(), record.albedo);
}

}  // namespace countershade
