#include "enhance/depth_usm.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "core/gaussian.h"
#include "enhance/lightness.h"
#include "enhance/registry.h"
#include "enhance/view_plan.h"
#include "render/ray_tracer.h"
#include "render/scene_loader.h"
#include "test_util.h"

namespace countershade {
namespace {

struct Rendered {
  std::shared_ptr<const View> view;
};

Rendered render_test_view(const testing::TempDir& dir, const std::string& json) {
  auto scene = std::make_shared<Scene>(load_scene(testing::write_file(dir / "scene.json", json)));
  return {render_view(scene)};
}

nlohmann::json op(const std::string& name, double kernel = 5.0) {
  return {{"operator", name}, {"kernel_percent", kernel}};
}

double sigma_of(const View& view, double kernel = 5.0) {
  return kernel / 100.0 * std::hypot(double(view.width()), double(view.height())) / 4.0;
}

// Luft et al.'s Fig. 4: three rectangles one behind the other, flat-shaded, no shadows: a white
// back wall, a white rectangle in front of it and a dark one in front of that.
const char* kThreeRectangles = R"({
  "version": 1,
  "camera": {"eye": [0, 0, 10], "target": [0, 0, 0], "projection": "orthographic", "height_world": 6,
             "width": 160, "height": 120},
  "render": {"spp": 1},
  "objects": [
    {"name": "back", "shape": {"type": "plane", "size": 20, "subdivisions": 2}, "transform": {"rotate": [90, 0, 0]},
     "material": {"albedo": 1.0}},
    {"name": "middle", "shape": {"type": "box", "size": [3, 2.4, 0.1]}, "transform": {"translate": [-1.0, 0.3, 1.5]},
     "material": {"albedo": 1.0}},
    {"name": "front", "shape": {"type": "box", "size": [2.0, 1.6, 0.1]}, "transform": {"translate": [0.8, -0.4, 3.0]},
     "material": {"albedo": 0.25}}
  ],
  "lights": [{"type": "ambient", "radiance": 1.0}]
})";

double lightness(const Composed& c, const View& v, size_t i) {
  return display_pixel_to_lab(&c.display.pixels[3 * i], v.encoding).L;
}

TEST(DepthUsm, LambdaZeroIsTheIdentityForEveryOperator) {
  testing::TempDir dir;
  Rendered r = render_test_view(dir, kThreeRectangles);
  for (const char* name : {"add", "contrast", "darken", "color"})
    for (const char* space : {"rgb", "lab"}) {
      if (std::string(name) == "color" && std::string(space) == "lab")
        continue;  // refused (hue shift)
      nlohmann::json o = op(name);
      o["space"] = space;
      Composed out = prepare_method("depth-usm", r.view, o)->compose(0.0);
      EXPECT_EQ(out.display.pixels, r.view->display.pixels) << name << " " << space;
    }
}

// ΔD is computed with the fast recursive Gaussian; at σ = 10 px (past the exact FIR's range) its
// blur of the depth steps stays within 2e-4 of the exact FIR's (the 4-digit recursive constants
// missed by about 1e-3 here, enough to move add at λ = −1.5 by more than a code level).
TEST(DepthUsm, SpatialImportanceMatchesTheExactGaussian) {
  testing::TempDir dir;
  Rendered r = render_test_view(dir, kThreeRectangles);
  SpatialImportance si = spatial_importance(*r.view, DepthMapping{}, 10.0);
  Image exact(si.depth.width, si.depth.height, 1);
  gaussian_blur_exact(si.depth.pixels.data(), exact.pixels.data(), si.depth.width, si.depth.height,
                      10.0);
  double worst = 0;
  for (size_t i = 0; i < exact.pixels.size(); ++i)
    worst = std::max(worst, std::abs(double(si.blurred.pixels[i]) - double(exact.pixels[i])));
  EXPECT_LT(worst, 2e-4);
}

TEST(DepthUsm, DarkenNeverBrightensAndLeavesForegroundAlone) {
  testing::TempDir dir;
  Rendered r = render_test_view(dir, kThreeRectangles);
  auto prepared = prepare_method("depth-usm", r.view, op("darken"));
  SpatialImportance si = spatial_importance(*r.view, DepthMapping{}, sigma_of(*r.view));
  Composed out = prepared->compose(0.8);
  int darkened = 0;
  for (size_t i = 0; i < r.view->lab.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      float before = r.view->display.pixels[3 * i + c], after = out.display.pixels[3 * i + c];
      EXPECT_LE(after, before);
      if (si.importance.pixels[i] >= 0) {
        EXPECT_EQ(after, before);
      }
      darkened += after < before;
    }
  EXPECT_GT(darkened, 500);
}

TEST(DepthUsm, AddAndDarkenAgreeOnTheBackgroundSide) {
  testing::TempDir dir;
  Rendered r = render_test_view(dir, kThreeRectangles);
  SpatialImportance si = spatial_importance(*r.view, DepthMapping{}, sigma_of(*r.view));
  for (double lambda : {-0.6, 0.6}) {
    Composed add = prepare_method("depth-usm", r.view, op("add"))->compose(lambda);
    Composed darken = prepare_method("depth-usm", r.view, op("darken"))->compose(lambda);
    int compared = 0;
    for (size_t i = 0; i < r.view->lab.size(); ++i) {
      if (si.importance.pixels[i] > 0) continue;  // background side: ΔD ≤ 0
      for (int c = 0; c < 3; ++c)
        EXPECT_EQ(add.display.pixels[3 * i + c], darken.display.pixels[3 * i + c]);
      compared += si.importance.pixels[i] < 0;
    }
    EXPECT_GT(compared, 500);
  }
}

TEST(DepthUsm, ColorAddsColdBehindAndWarmInFront) {
  testing::TempDir dir;
  std::string grey = kThreeRectangles;  // mid-grey surfaces so nothing clips
  for (size_t p; (p = grey.find("\"albedo\": 1.0")) != std::string::npos;)
    grey.replace(p, 13, "\"albedo\": 0.3");
  Rendered r = render_test_view(dir, grey);
  const glm::dvec3 cold(-0.1, -0.05, 0.15), warm(0.15, 0.1, -0.1);  // the defaults
  SpatialImportance si = spatial_importance(*r.view, DepthMapping{}, sigma_of(*r.view));
  Composed out = prepare_method("depth-usm", r.view, op("color"))->compose(1.5);
  EXPECT_EQ(out.clipped_pixels, 0u);
  int behind = 0, in_front = 0;
  for (size_t i = 0; i < r.view->lab.size(); ++i) {
    double d = si.importance.pixels[i];
    if (std::abs(d) < 1e-3) continue;
    glm::dvec3 shift;
    for (int c = 0; c < 3; ++c)
      shift[c] = out.display.pixels[3 * i + c] - r.view->display.pixels[3 * i + c];
    const glm::dvec3& colour = d < 0 ? cold : warm;
    // The shift is a positive multiple of the one colour: parallel, same direction.
    double scale = glm::dot(shift, colour) / glm::dot(colour, colour);
    EXPECT_GT(scale, 0.0);
    EXPECT_LT(glm::length(shift - scale * colour), 1e-5) << i;
    (d < 0 ? behind : in_front)++;
  }
  EXPECT_GT(behind, 100);
  EXPECT_GT(in_front, 100);
}

// Darken separates every rectangle: the far side of each depth edge steps down in lightness.
TEST(DepthUsm, FigureFourDarkenSeparatesEveryRectangleContrastCannotSeparateWhiteOnWhite) {
  testing::TempDir dir;
  Rendered r = render_test_view(dir, kThreeRectangles);
  const GBuffer& g = r.view->render.gbuffer;
  Composed darken = prepare_method("depth-usm", r.view, op("darken"))->compose(1.0);
  Composed contrast = prepare_method("depth-usm", r.view, op("contrast"))->compose(1.0);
  // Walk along a row through back | middle | front and look just beside each edge.
  int y = g.height / 2 - 4;
  auto id = [&](int x) { return g.object[g.index(x, y)]; };
  std::vector<std::pair<int, int>>
      edges;  // x of the far-side pixel next to an edge, and the far object
  for (int x = 1; x < g.width; ++x)
    if (id(x) != id(x - 1)) {
      int far_x =
          id(x) < id(x - 1) ? x : x - 1;  // lower object id = farther (back 0, middle 1, front 2)
      edges.emplace_back(far_x, std::min(id(x), id(x - 1)));
    }
  ASSERT_GE(edges.size(), 2u);
  for (auto [x, object] : edges) {
    // Compare with the same surface 25 px away from the edge (away from the kernel's reach).
    int step = x < g.width / 2 ? -1 : 1;
    if (id(x + step) != object) step = -step;
    int far_x = x + 25 * step;
    ASSERT_EQ(id(far_x), object);
    size_t near_i = g.index(x, y), far_i = g.index(far_x, y);
    EXPECT_LT(lightness(darken, *r.view, near_i), lightness(darken, *r.view, far_i) - 2.0)
        << "darken: no lightness step on the far side of the edge at x = " << x;
  }
  // White-on-white (middle in front of back): contrast changes nothing there.
  int changed_white = 0, changed_dark_edge = 0;
  for (size_t i = 0; i < r.view->lab.size(); ++i) {
    bool white = r.view->lab[i].L > 99.9;
    bool changed = std::abs(lightness(contrast, *r.view, i) - r.view->lab[i].L) > 1e-3;
    changed_white += white && changed;
    changed_dark_edge += !white && changed;
  }
  EXPECT_EQ(changed_white, 0);
  EXPECT_GT(changed_dark_edge, 50) << "the dark rectangle's edge has colour contrast to amplify";
}

// A dark card turned by 25° in front of a lit wall, flat-shaded: its outline runs across the
// pixels at every phase, so its anti-aliased pixels cover every share of wall.
const char* kTurnedCard = R"({
  "version": 1,
  "camera": {"eye": [0, 0, 10], "target": [0, 0, 0], "projection": "orthographic", "height_world": 6,
             "width": 160, "height": 120},
  "render": {"spp": 64, "seed": 5},
  "objects": [
    {"name": "wall", "shape": {"type": "plane", "size": 20, "subdivisions": 2}, "transform": {"rotate": [90, 0, 0]},
     "material": {"albedo": 0.6}},
    {"name": "card", "shape": {"type": "box", "size": [3, 2, 0.1]}, "transform": {"rotate": [0, 0, 25], "translate": [0, 0, 2]},
     "material": {"albedo": 0.15}}
  ],
  "lights": [{"type": "ambient", "radiance": 1.0}]
})";

// Darkening falls on the wall behind the card. A pixel of the outline is part card and part wall,
// and only its wall part may be darkened: its change must be the wall's share of what a pixel of
// wall there would get. With one depth per pixel it got all of it or none, and the anti-aliased
// outline became a staircase.
TEST(DepthUsm, DarkeningFollowsTheWallsShareOfAnOutlinePixel) {
  testing::TempDir dir;
  const auto view = render_test_view(dir, kTurnedCard).view;
  const double lambda = 0.5, sigma = 4.0;
  const Composed out =
      prepare_method("depth-usm", view, {{"operator", "darken"}, {"sigma_px", sigma}})
          ->compose(lambda);
  const SpatialImportance si = spatial_importance(*view, {}, sigma);
  const int w = view->width();
  auto linear = [&](size_t p) { return view->encoding.decode(view->display.pixels[3 * p]); };
  const size_t wall = 0, card = size_t(60) * w + 80;  // a corner and the centre
  const double wall_linear = linear(wall), card_linear = linear(card),
               wall_depth = si.depth.pixels[wall];
  int outline_pixels = 0;
  for (size_t p = 0; p < si.depth.pixels.size(); ++p) {
    const double share =
        (linear(p) - card_linear) / (wall_linear - card_linear);  // of the pixel's area
    const double full = lambda * std::min(double(si.blurred.pixels[p]) - wall_depth, 0.0);
    if (share < 0.2 || share > 0.8 || full > -0.05) continue;
    ++outline_pixels;
    const double change = double(out.display.pixels[3 * p]) - double(view->display.pixels[3 * p]);
    EXPECT_NEAR(change, share * full, 0.25 * -full + 2.0 / 255.0)
        << "pixel " << p % w << "," << p / w << " wall share " << share;
  }
  EXPECT_GT(outline_pixels, 100);
}

TEST(DepthUsm, BackgroundIsFarAndDepthIsNormalisedOverValidPixels) {
  auto view = make_image_view(Image(4, 1, 3, 0.5f), {0.0f, 2.0f, 4.0f, INFINITY},
                              DisplayEncoding::srgb(), 8);
  SpatialImportance si = spatial_importance(*view, DepthMapping{}, 1.0);
  EXPECT_EQ(std::vector<float>(si.depth.pixels.begin(), si.depth.pixels.end()),
            (std::vector<float>{1.0f, 0.0f, 1.0f, 1.0f}));
  DepthMapping zbuffer;
  zbuffer.zbuffer = true;
  zbuffer.z_near = 1.0;
  zbuffer.z_far = 8.0;
  si = spatial_importance(*view, zbuffer, 1.0);
  EXPECT_FLOAT_EQ(si.depth.pixels[1], 0.0f);
  EXPECT_FLOAT_EQ(si.depth.pixels[2], 1.0f);
}

// A fixed depth range: D of a point no longer depends on what else the image holds (in a sequence,
// a moving object that comes nearer than everything else would change every pixel's D), and depths
// outside the range are clamped.
TEST(DepthUsm, AFixedDepthRangeMakesDIndependentOfTheRestOfTheImage) {
  DepthMapping fixed;
  fixed.range = std::make_pair(1.0, 9.0);
  const std::vector<float> without = {5.0f, 3.0f, 7.0f, INFINITY},
                           with_near_object = {5.0f, 3.0f, 0.5f, INFINITY};
  const auto a = make_image_view(Image(4, 1, 3, 0.5f), without, DisplayEncoding::srgb(), 8);
  const auto b =
      make_image_view(Image(4, 1, 3, 0.5f), with_near_object, DisplayEncoding::srgb(), 8);
  EXPECT_NE(spatial_importance(*a, DepthMapping{}, 1.0).depth.pixels[0],
            spatial_importance(*b, DepthMapping{}, 1.0).depth.pixels[0]);
  const SpatialImportance sa = spatial_importance(*a, fixed, 1.0),
                          sb = spatial_importance(*b, fixed, 1.0);
  EXPECT_EQ(sa.depth.pixels[0], 0.5f);
  EXPECT_EQ(sb.depth.pixels[0], 0.5f);
  EXPECT_EQ(sa.depth.pixels[1], 0.25f);
  EXPECT_EQ(sb.depth.pixels[2], 0.0f);  // nearer than the range: clamped
  EXPECT_EQ(sb.depth.pixels[3], 1.0f);  // background
}

std::shared_ptr<const MethodParameters> parse(const nlohmann::json& j) {
  return method_named("depth-usm", "test")
      .parse(ParameterBag::from_json(j, "exp.json", "methods[1]"));
}

TEST(DepthUsm, ValidatesItsOptions) {
  EXPECT_THROW(parse(nlohmann::json::object()), InputError);  // no kernel
  EXPECT_THROW(parse(op("darken", 0.0)), InputError);
  EXPECT_THROW(parse(op("darken", 51.0)), InputError);
  EXPECT_THROW(parse(op("blur")), InputError);
  EXPECT_NO_THROW(parse(op("darken", 50.0)));
  // Keys of other operators are unused, hence errors.
  nlohmann::json cold = op("darken");
  cold["cold"] = {0, 0, 1};
  std::string message = testing::input_error_of([&] { parse(cold); });
  EXPECT_NE(message.find("methods[1].cold: depth-usm has no parameter 'cold'"), std::string::npos)
      << message;
  for (const nlohmann::json& range : {nlohmann::json::array({9, 1}), nlohmann::json::array({-1, 2}),
                                      nlohmann::json::array({3})}) {
    nlohmann::json j = op("darken");
    j["depth_range"] = range;
    message = testing::input_error_of([&] { parse(j); });
    EXPECT_NE(message.find("methods[1].depth_range: expected NEAR,FAR with 0 <= NEAR < FAR"),
              std::string::npos)
        << message;
  }
  nlohmann::json ok = op("darken");
  ok["depth_range"] = {2, 12};
  EXPECT_NO_THROW(parse(ok));
}

// The color operator's point is a hue shift (cold behind, warm in front); the lightness-only lab
// space used to collapse it to the luminance of the colours. The combination is now refused.
TEST(DepthUsm, ColorInLabIsRefusedBecauseItWouldDropTheHueShift) {
  nlohmann::json o = op("color");
  o["space"] = "lab";
  std::string message = testing::input_error_of([&] { parse(o); });
  EXPECT_NE(message.find("methods[1].space"), std::string::npos) << message;
  EXPECT_NE(message.find("hue"), std::string::npos) << message;
}

// Equalisation maps the lowest value present to 0: a large dark background stays dark. It used to
// be lifted to the background's share of the pixels (here 80 % of the range).
TEST(DepthUsm, EqualisationKeepsTheDarkestValueAtZero) {
  std::vector<float> values(1000, 0.1f);
  for (int i = 0; i < 200; ++i) values[size_t(i)] = 0.2f + 0.7f * float(i) / 199.0f;
  GlobalContrast equalize(values, 1.0, true);
  EXPECT_NEAR(equalize(0.1), 0.0, 1e-12);
  EXPECT_NEAR(equalize(0.9), 1.0, 1e-12);
  EXPECT_NEAR(equalize(0.55), 0.5, 0.02);  // the middle of the spread-out values
  GlobalContrast stretch(values, 1.0, false);
  EXPECT_NEAR(stretch(0.1), 0.0, 1e-3);
}

}  // namespace
}  // namespace countershade
