#include "measures/flicker.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/error.h"
#include "core/gaussian.h"
#include "enhance/lightness.h"
#include "enhance/view_plan.h"
#include "render/ray_tracer.h"
#include "render/renderer.h"
#include "render/scene_animation.h"

namespace countershade {
namespace {

std::vector<float> blurred(std::span<const float> values, const View& view, double sigma) {
  std::vector<float> out(values.size());
  gaussian_blur(values.data(), out.data(), view.width(), view.height(), sigma);
  return out;
}

// The enhancement layer of each channel in levels of 8-bit output, whatever the bit depth: the
// unit an object's change is stated in.
std::array<std::vector<float>, 3> level_layers(const View& view, const Image& enhanced) {
  std::array<std::vector<float>, 3> out;
  for (size_t c = 0; c < 3; ++c) {
    out[c].resize(size_t(view.width()) * size_t(view.height()));
    for (size_t i = 0; i < out[c].size(); ++i)
      out[c][i] = 255.0f * (enhanced.pixels[3 * i + c] - view.display.pixels[3 * i + c]);
  }
  return out;
}

// A rendered frame: the planes its FlickerFrame's spans point into (a move keeps them valid).
struct RenderedFrame {
  std::vector<float> layer, plain;
  FlickerFrame frame;
};

RenderedFrame render_frame(const Scene& base, int index, const FlickerRender& render,
                           const FlickerOptions& options) {
  auto scene = std::make_shared<const Scene>(scene_at(base, base.animation->time_of(index)));
  ViewPlan plan;
  plan.uses.push_back({render.method, render.parameters, nlohmann::json::object()});
  plan.max_abs_lambda = std::abs(render.lambda);
  ViewOptions view_options;
  view_options.threads = render.threads;
  view_options.bits = render.bits;
  RenderedFrame out;
  FlickerFrame& f = out.frame;
  f.view = render_view(scene, plan, view_options);
  const auto prepared =
      render.method->prepare(make_use_context(f.view, 0, render.threads), *render.parameters);
  const Image enhanced = prepared->compose(render.lambda).display;
  out.layer = render.component == FlickerComponent::mask ? prepared->mask()
                                                         : enhancement_layer(*f.view, enhanced);
  if (out.layer.empty())
    throw InputError("--component mask: " + render.method->name() +
                     " subtracts no low-pass signal, so it has no mask (usm3d, usm2d, depth-usm "
                     "and texture-filter "
                     "with filter unsharp have one)");
  out.plain = view_lightness(*f.view);
  f.layer = out.layer;
  f.plain = out.plain;
  if (options.object >= 0) f.levels = level_layers(*f.view, enhanced);
  if (options.has_region() && options.region_scene)
    f.region =
        region_pixels(*geometry_view(std::make_shared<const Scene>(scene_at(
                                         *options.region_scene, base.animation->time_of(index))),
                                     render.threads),
                      options);
  if (options.scale_px > 0) {
    f.layer_at_scale = blurred(f.layer, *f.view, options.scale_px);
    f.plain_at_scale = blurred(f.plain, *f.view, options.scale_px);
  }
  return out;
}

// Per pixel of the object seen in both frames, the largest change over the three channels (−1
// elsewhere).
std::vector<float> object_largest_change(const FlickerFrame& a, const FlickerFrame& b,
                                         const CarryPoint& carry, int object) {
  std::vector<float> largest(a.layer.size(), -1.0f);
  for (size_t c = 0; c < 3; ++c) {
    std::vector<float> differences;
    reprojection_rms(*a.view, a.levels[c], *b.view, b.levels[c], carry, &differences);
    for (size_t i = 0; i < differences.size(); ++i)
      if (a.view->object_at(i) == object && !std::isnan(differences[i]))
        largest[i] = std::max(largest[i], differences[i]);
  }
  return largest;
}

// The largest change and its 99th percentile over the object's pixels; with `stable`, only over
// those whose plain L* changes by at most that much.
ObjectChange object_change(const std::vector<float>& largest,
                           const std::vector<float>& plain_differences,
                           std::optional<double> stable) {
  std::vector<float> values;
  for (size_t i = 0; i < largest.size(); ++i)
    if (largest[i] >= 0 && (!stable || plain_differences[i] <= *stable))
      values.push_back(largest[i]);
  ObjectChange out;
  out.pixels = values.size();
  if (values.empty()) return out;
  std::sort(values.begin(), values.end());
  out.max = values.back();
  out.p99 = values[size_t(0.99 * double(values.size() - 1))];
  return out;
}

// For every pixel, the squared distance to the nearest pixel of `object` (large where it has none):
// per row the distance along it, then the nearest over the rows within `radius`.
std::vector<double> squared_distance_to(const View& view, int object, int radius) {
  const int w = view.width(), h = view.height();
  const double far = 1e18;
  std::vector<double> along(size_t(w) * h, far), out(size_t(w) * h, far);
  for (int y = 0; y < h; ++y) {
    double* row = along.data() + size_t(y) * w;
    for (int pass = 0; pass < 2; ++pass) {  // left to right, then right to left
      double d = far;
      for (int k = 0; k < w; ++k) {
        const int x = pass ? w - 1 - k : k;
        d = view.object_at(size_t(y) * w + x) == object ? 0.0 : d + 1.0;
        row[x] = std::min(row[x], d);
      }
    }
  }
  for (int y = 0; y < h; ++y)
    for (int dy = -radius; dy <= radius; ++dy) {
      if (y + dy < 0 || y + dy >= h) continue;
      for (int x = 0; x < w; ++x) {
        const double a = along[size_t(y + dy) * w + x];
        out[size_t(y) * w + x] = std::min(out[size_t(y) * w + x], a * a + double(dy) * dy);
      }
    }
  return out;
}

// The RMS of `differences` over the counted pixels (not NaN) of `region`.
Reprojection rms_in(const std::vector<float>& differences, const std::vector<char>& region) {
  Reprojection out;
  double sum = 0;
  for (size_t i = 0; i < differences.size(); ++i)
    if (region[i] && !std::isnan(differences[i]))
      sum += double(differences[i]) * differences[i], ++out.pixels;
  out.rms = out.pixels ? std::sqrt(sum / double(out.pixels)) : 0.0;
  return out;
}

}  // namespace

std::vector<char> region_pixels(const View& view, const FlickerOptions& o) {
  const size_t n = size_t(view.width()) * view.height();
  std::vector<char> in(n, 1);
  const int radius = int(std::ceil(o.within_px));
  const std::vector<double> d2 =
      o.near >= 0 ? squared_distance_to(view, o.near, radius) : std::vector<double>{};
  for (size_t i = 0; i < n; ++i) {
    if (o.on >= 0 && view.object_at(i) != o.on) in[i] = 0;
    if (o.near >= 0 && (d2[i] > o.within_px * o.within_px || view.object_at(i) == o.near))
      in[i] = 0;
  }
  return in;
}

std::shared_ptr<const View> geometry_view(std::shared_ptr<const Scene> scene, int threads) {
  auto view = std::make_shared<View>();
  const RayTracer tracer(*scene);
  view->render.gbuffer = render_gbuffer(*scene, tracer, threads);
  view->depth = view->render.gbuffer.depth;
  view->display = Image(scene->camera.width, scene->camera.height, 1);
  view->scene = std::move(scene);
  return view;
}

PlainChange plain_change(const FlickerFrame& a, const FlickerFrame& b, const CarryPoint& carry) {
  PlainChange out;
  out.rms = reprojection_rms(*a.view, a.plain, *b.view, b.plain, carry, &out.differences);
  return out;
}

PairFlicker pair_flicker(const FlickerFrame& a, const FlickerFrame& b, const CarryPoint& carry,
                         const PlainChange& plain, const FlickerOptions& options) {
  PairFlicker out;
  out.layer = reprojection_rms(*a.view, a.layer, *b.view, b.layer, carry, &out.differences);
  if (options.scale_px > 0) {
    out.at_scale =
        reprojection_rms(*a.view, a.layer_at_scale, *b.view, b.layer_at_scale, carry).rms;
    out.plain_at_scale =
        reprojection_rms(*a.view, a.plain_at_scale, *b.view, b.plain_at_scale, carry).rms;
  }
  if (options.stable > 0)
    out.stable = rms_where_stable(out.differences, plain.differences, options.stable);
  if (options.has_region()) {
    const std::vector<char> region = a.region.empty() ? region_pixels(*a.view, options) : a.region;
    out.region = rms_in(out.differences, region);
    out.plain_region = rms_in(plain.differences, region);
  }
  if (options.object < 0) return out;
  const std::vector<float> largest = object_largest_change(a, b, carry, options.object);
  out.object = object_change(largest, plain.differences, std::nullopt);
  if (options.stable > 0)
    out.object_stable = object_change(largest, plain.differences, options.stable);
  return out;
}

void measure_rendered_flicker(const Scene& base, int first, int last, const FlickerRender& render,
                              const FlickerOptions& options, const FlickerPairSink& sink,
                              const std::function<void(double)>& progress) {
  RenderedFrame previous = render_frame(base, first, render, options);
  for (int f = first + 1; f <= last; ++f) {
    RenderedFrame current = render_frame(base, f, render, options);
    const CarryPoint carry = carry_between_frames(base, f - 1, f);
    const PlainChange plain = plain_change(previous.frame, current.frame, carry);
    sink(f, previous.frame, current.frame, plain,
         pair_flicker(previous.frame, current.frame, carry, plain, options));
    previous = std::move(current);
    if (progress) progress(double(f - first) / double(last - first));
  }
}

int named_object(const Scene& scene, const std::string& name, const char* option) {
  if (name.empty()) return -1;
  for (size_t k = 0; k < scene.objects.size(); ++k)
    if (scene.objects[k].name == name) return int(k);
  throw InputError(std::string(option) + ": " + scene.file.string() + " has no object called '" +
                   name + "'");
}

void remove_object(Scene& scene, const std::string& name) {
  const int k = named_object(scene, name, "--without");
  scene.objects.erase(scene.objects.begin() + k);
  auto& paths = scene.animation->objects;
  std::erase_if(paths, [k](const ObjectPath& p) { return p.object == size_t(k); });
  for (ObjectPath& p : paths)
    if (p.object > size_t(k)) --p.object;
}

}  // namespace countershade
