// The congruence score against a second, plain implementation of docs/methods.md ("Congruence
// score"), written separately in double precision with other formulas where the definition allows
// (a 2D convolution instead of two passes, the eigenvector from its angle), on fields with an
// irregular foreground that touches the image border, flat patches and noise, and on a rendered
// mesh; with the paper's signed clamp and with the absolute difference.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "core/random.h"
#include "enhance/lightness.h"
#include "enhance/method.h"
#include "enhance/view_plan.h"
#include "measures/congruence.h"
#include "render/scene_loader.h"
#include "test_util.h"

namespace countershade {
namespace {

using Plane = std::vector<double>;

struct Field {
  int w, h;
  Plane v;
  double at(int x, int y) const { return v[size_t(y) * w + x]; }
};

bool foreground(double depth) { return std::isfinite(depth) && depth > 0; }

// Foreground pixels whose eight neighbours lie in the image and are foreground.
std::vector<bool> reference_interior(const Field& depth) {
  std::vector<bool> in(depth.v.size(), false);
  for (int y = 0; y < depth.h; ++y)
    for (int x = 0; x < depth.w; ++x) {
      bool all = x > 0 && y > 0 && x < depth.w - 1 && y < depth.h - 1;
      for (int dy = -1; all && dy <= 1; ++dy)
        for (int dx = -1; all && dx <= 1; ++dx) all = foreground(depth.at(x + dx, y + dy));
      in[size_t(y) * depth.w + x] = all;
    }
  return in;
}

// Central differences, one-sided at the border.
double reference_derivative(const Field& f, int x, int y, int dx, int dy) {
  const int n = dx ? f.w : f.h, k = dx ? x : y;
  const int lo = std::max(0, k - 1), hi = std::min(n - 1, k + 1);
  const double span = hi - lo;
  return (f.at(x + dx * (hi - k), y + dy * (hi - k)) - f.at(x - dx * (k - lo), y - dy * (k - lo))) /
         span;
}

// The Gaussian of σ = 2 over ±8 pixels as one 2D window, clamp-to-edge.
Plane reference_blur(const Plane& in, int w, int h) {
  constexpr int r = 8, side = 2 * r + 1;
  double window[side][side], total = 0;
  for (int j = -r; j <= r; ++j)
    for (int i = -r; i <= r; ++i)
      total += window[j + r][i + r] = std::exp(-(i * i + j * j) / (2 * 2.0 * 2.0));
  Plane out(in.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double sum = 0;
      for (int j = -r; j <= r; ++j)
        for (int i = -r; i <= r; ++i)
          sum += window[j + r][i + r] *
                 in[size_t(std::clamp(y + j, 0, h - 1)) * w + std::clamp(x + i, 0, w - 1)];
      out[size_t(y) * w + x] = sum / total;
    }
  return out;
}

struct ReferenceFlow {
  Plane vx, vy, e;
};

ReferenceFlow reference_flow(const Field& f, const std::vector<bool>& interior) {
  const size_t n = f.v.size();
  Plane xx(n, 0.0), xy(n, 0.0), yy(n, 0.0);
  for (int y = 0; y < f.h; ++y)
    for (int x = 0; x < f.w; ++x) {
      const size_t i = size_t(y) * f.w + x;
      if (!interior[i]) continue;
      const double gx = reference_derivative(f, x, y, 1, 0),
                   gy = reference_derivative(f, x, y, 0, 1);
      xx[i] = gx * gx, xy[i] = gx * gy, yy[i] = gy * gy;
    }
  xx = reference_blur(xx, f.w, f.h), xy = reference_blur(xy, f.w, f.h),
  yy = reference_blur(yy, f.w, f.h);
  ReferenceFlow out{Plane(n, 0.0), Plane(n, 0.0), Plane(n, 0.0)};
  for (size_t i = 0; i < n; ++i) {
    const double a = xx[i], b = xy[i], c = yy[i];
    out.e[i] = (a + c) / 2;
    if (std::sqrt((a - c) * (a - c) + 4 * b * b) < 1e-12) continue;  // λ1 − λ2
    const double angle = 0.5 * std::atan2(2 * b, a - c);             // the major axis
    out.vx[i] = std::cos(angle), out.vy[i] = std::sin(angle);
  }
  return out;
}

void reference_normalise(Plane& e, const std::vector<bool>& interior) {
  std::vector<double> inside;
  for (size_t i = 0; i < e.size(); ++i)
    if (interior[i]) inside.push_back(e[i]);
  std::sort(inside.begin(), inside.end());
  double p = 0;
  if (!inside.empty()) {
    const double h = 0.99 * double(inside.size() - 1);
    const size_t k = size_t(h);
    p = k + 1 < inside.size() ? inside[k] + (h - double(k)) * (inside[k + 1] - inside[k])
                              : inside[k];
  }
  for (double& v : e) v = p > 0 ? std::clamp(v / p, 0.0, 1.0) : 0.0;
}

struct Reference {
  double score;
  Plane map;
};

// The score's penalty ⌊e_c − e_s⌋ (signed) or ⌊|e_c − e_s|⌋ (absolute), ⌊·⌋ clamping to [0, 1].
double reference_penalty(double ec, double es, bool absolute) {
  const double d = absolute ? std::fabs(ec - es) : ec - es;
  return d <= 0 ? 0.0 : (d >= 1 ? 1.0 : d);
}

Reference reference_congruence(const Field& lightness, const Field& depth, bool absolute = false) {
  const std::vector<bool> interior = reference_interior(depth);
  Field shading = lightness, shape = depth;
  for (double& v : shading.v) v /= 100.0;
  double lo = INFINITY, hi = -INFINITY;
  for (double d : depth.v)
    if (foreground(d)) lo = std::min(lo, d), hi = std::max(hi, d);
  for (double& d : shape.v) d = foreground(d) ? (hi > lo ? (d - lo) / (hi - lo) : 0.0) : 1.0;
  ReferenceFlow s = reference_flow(shading, interior), c = reference_flow(shape, interior);
  reference_normalise(s.e, interior);
  reference_normalise(c.e, interior);
  Reference out{0.0, Plane(depth.v.size(), 0.0)};
  double sum = 0, weight = 0;
  for (size_t i = 0; i < interior.size(); ++i) {
    if (!interior[i]) continue;
    out.map[i] = c.e[i] * (1 - reference_penalty(c.e[i], s.e[i], absolute)) *
                 std::abs(c.vx[i] * s.vx[i] + c.vy[i] * s.vy[i]);
    sum += out.map[i], weight += c.e[i];
  }
  out.score = weight > 0 ? sum / weight : 0.0;
  return out;
}

// A scene of w×h: two overlapping bumps on a tilted base whose foreground is irregular and runs
// off the image's left and bottom edges; shading from a light with noise, a flat patch and a
// step (so that isotropic, anisotropic and clamped magnitudes all occur).
struct Fields {
  Image lightness, depth;
};

Fields make_scene(int w, int h, uint64_t seed, double noise) {
  Fields s{Image(w, h, 1), Image(w, h, 1)};
  SampleStream random(seed, 0, 0, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double u = double(x) / w, v = double(y) / h;
      const bool inside = (u - 0.35) * (u - 0.35) + (v - 0.6) * (v - 0.6) < 0.2 ||
                          (u > 0.55 && v > 0.3 && u + v < 1.5);
      const double bump = std::exp(-((u - 0.3) * (u - 0.3) + (v - 0.5) * (v - 0.5)) / 0.02) +
                          0.5 * std::exp(-((u - 0.7) * (u - 0.7) + (v - 0.6) * (v - 0.6)) / 0.005);
      const double z = 10.0 + 3.0 * u + 2.0 * v - 2.0 * bump;
      s.depth.at(x, y) =
          inside ? float(z) : (x % 7 == 0 ? 0.0f : std::numeric_limits<float>::infinity());
      double l = 50.0 + 30.0 * std::sin(9.0 * u + 4.0 * bump) + noise * (random.next() - 0.5);
      if (u > 0.6 && u < 0.7 && v > 0.4 && v < 0.5) l = 40.0;  // flat: isotropic tensors
      if (v > 0.8) l += 25.0;                                  // a step
      s.lightness.at(x, y) = float(std::clamp(l, 0.0, 100.0));
    }
  return s;
}

Field field_of(const Image& image) {
  return {image.width, image.height, Plane(image.pixels.begin(), image.pixels.end())};
}

void expect_agreement(const Image& lightness, const Image& depth, const std::string& what) {
  for (bool absolute : {false, true}) {
    const Congruence ours =
        congruence(lightness, depth,
                   {absolute ? CongruencePenalty::absolute : CongruencePenalty::signed_clamp});
    const Reference ref = reference_congruence(field_of(lightness), field_of(depth), absolute);
    EXPECT_GT(ref.score, 0.05) << what;
    EXPECT_NEAR(ours.score, ref.score, 1e-5) << what << (absolute ? ", absolute" : ", signed");
    double worst = 0;
    for (size_t i = 0; i < ref.map.size(); ++i)
      worst = std::max(worst, std::abs(double(ours.map.pixels[i]) - ref.map[i]));
    EXPECT_LT(worst, 1e-4) << what << (absolute ? ", absolute" : ", signed");
  }
}

TEST(CongruenceReference, AgreesWithASeparateImplementationOfTheDefinition) {
  for (const auto& [w, h, seed, noise] :
       {std::tuple{96, 64, 1u, 0.0}, std::tuple{80, 72, 2u, 20.0}, std::tuple{64, 96, 3u, 100.0}}) {
    const Fields scene = make_scene(w, h, seed, noise);
    expect_agreement(
        scene.lightness, scene.depth,
        std::to_string(w) + "x" + std::to_string(h) + " noise " + std::to_string(noise));
  }
}

// A rendered mesh the implementation has never seen: a bumpy, faceted ball in perspective under a
// raking light, scored from its display image and depth buffer.
TEST(CongruenceReference, AgreesWithASeparateImplementationOnARenderedMesh) {
  testing::TempDir dir;
  const auto scene = std::make_shared<Scene>(load_scene(testing::write_file(dir / "ball.json", R"({
    "version": 1,
    "camera": {"eye": [0.4, 0.3, 3.2], "target": [0, 0, 0], "fov": 40, "width": 112, "height": 84},
    "render": {"spp": 4},
    "objects": [{"shape": {"type": "sphere", "radius": 1, "subdivisions": 2}, "crease_angle": 0, "material": {"albedo": 0.7}},
                {"shape": {"type": "box", "size": [0.5, 0.5, 0.5]}, "transform": {"translate": [0.7, -0.5, 0.9]}}],
    "lights": [{"type": "directional", "direction": [-0.8, 0.3, 0.4], "irradiance": 2.5}, {"type": "ambient", "radiance": 0.05}]
  })")));
  const auto view = render_view(scene);
  const LabPixels lab = display_to_lab(view->display, view->encoding, 0);
  Image lightness(view->display.width, view->display.height, 1),
      depth(lightness.width, lightness.height, 1);
  for (size_t i = 0; i < lab.size(); ++i)
    lightness.pixels[i] = float(lab[i].L), depth.pixels[i] = view->depth[i];
  expect_agreement(lightness, depth, "rendered ball");
}

// Shading stronger than shape (e_s > e_c) costs nothing under the signed clamp and lowers a pixel's
// term under the absolute difference: the signed map is never below the absolute one, and the two
// readings differ on the whole.
TEST(CongruenceReference, TheSignedClampDoesNotPenaliseExaggeration) {
  const Fields scene = make_scene(96, 64, 1, 20.0);
  const Congruence ours = congruence(scene.lightness, scene.depth);
  const Congruence absolute =
      congruence(scene.lightness, scene.depth, {CongruencePenalty::absolute});
  for (size_t i = 0; i < ours.map.pixels.size(); ++i)
    ASSERT_GE(ours.map.pixels[i], absolute.map.pixels[i]) << i;
  EXPECT_GT(ours.score, absolute.score + 0.01);
}

// The reference itself must be able to disagree: a shading turned by 90° scores differently.
TEST(CongruenceReference, TheComparisonSeesAChangedImage) {
  const Fields scene = make_scene(96, 64, 1, 0.0);
  Image turned = scene.lightness;
  for (int y = 0; y < turned.height; ++y)
    for (int x = 0; x < turned.width; ++x)
      turned.at(x, y) = scene.lightness.at(x, (y + 5) % turned.height);
  const Reference ref = reference_congruence(field_of(scene.lightness), field_of(scene.depth));
  EXPECT_GT(std::abs(congruence(turned, scene.depth).score - ref.score), 1e-3);
}

}  // namespace
}  // namespace countershade
