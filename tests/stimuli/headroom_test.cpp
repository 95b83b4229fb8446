// Headroom against clipping (an experiment's "headroom"): the search for the exposure, and a set
// that clips at the top of its grid without it and passes the audit's clipping check with it.

#include "stimuli/headroom.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "audit/audit.h"
#include "core/error.h"
#include "formats/manifest.h"
#include "set_test_util.h"
#include "stimuli/experiment.h"
#include "stimuli/stimulus_set.h"
#include "test_util.h"

namespace countershade {
namespace {

namespace fs = std::filesystem;

TEST(Headroom, TheSearchFindsTheSmallestExposureDropAgainstWhite) {
  // White clipping that falls linearly as the exposure drops: within 0.01 from −1.0 stops down.
  int calls = 0;
  auto linear = [&](const Headroom& h) {
    ++calls;
    EXPECT_EQ(h.black_level, 0.0);
    return Clipped{std::max(0.0, 0.05 + 0.04 * h.exposure_stops), 0.0};
  };
  const Headroom found = find_headroom(linear, 0.01);
  EXPECT_LE(found.exposure_stops, -1.0);
  EXPECT_GE(found.exposure_stops, -1.05);
  EXPECT_EQ(found.black_level, 0.0);
  EXPECT_LE(calls, 10);
  // Already within the limit: no change, one look.
  calls = 0;
  const Headroom none = find_headroom(
      [&](const Headroom&) {
        return ++calls, Clipped{0.005, 0.004};
      },
      0.01);
  EXPECT_EQ(none.exposure_stops, 0.0);
  EXPECT_EQ(none.black_level, 0.0);
  EXPECT_EQ(calls, 1);
  // A share that does not fall: no change is worth making.
  EXPECT_EQ(find_headroom(
                [](const Headroom&) {
                  return Clipped{0.2, 0.0};
                },
                0.01)
                .exposure_stops,
            0.0);
  EXPECT_EQ(find_headroom(
                [](const Headroom&) {
                  return Clipped{0.0, 0.2};
                },
                0.01)
                .black_level,
            0.0);
  // One that falls but never far enough: the end's neighbour, where it gave up.
  auto slow = [](const Headroom& h) { return Clipped{0.5 + 0.01 * h.exposure_stops, 0.0}; };
  EXPECT_EQ(find_headroom(slow, 0.01, {-0.25, -2, 0.05}).exposure_stops, -1.0);
}

TEST(Headroom, TheSearchRaisesTheBlackLevelAgainstBlackAtTheExposureItChose) {
  // Black clipping that falls as the black level rises: within 0.01 from 0.06 up. The exposure
  // is not touched for it (raising it would clip white).
  auto black = [](const Headroom& h) {
    EXPECT_EQ(h.exposure_stops, 0.0);
    return Clipped{0.0, std::max(0.0, 0.016 - 0.1 * h.black_level)};
  };
  const Headroom up = find_headroom(black, 0.01);
  EXPECT_EQ(up.exposure_stops, 0.0);
  EXPECT_GE(up.black_level, 0.06);
  EXPECT_LE(up.black_level, 0.06 + 1.0 / 256);
  // Both ends over the limit: the exposure drop first (which darkens, so more black clips), then
  // the black level at that exposure until both ends together are within the limit. The lift
  // compresses the lightness scale, so white clips less too, as under methods that work in L*.
  std::vector<Headroom> tried;
  auto both = [&](const Headroom& h) {
    tried.push_back(h);
    return Clipped{std::max(0.0, 0.02 + 0.02 * h.exposure_stops - 0.05 * h.black_level),
                   std::max(0.0, 0.02 - 0.01 * h.exposure_stops - 0.2 * h.black_level)};
  };
  const Headroom found = find_headroom(both, 0.01);
  EXPECT_LE(found.exposure_stops, -0.5);
  EXPECT_GE(found.exposure_stops, -0.55);
  EXPECT_GE(found.black_level, 0.1);  // at −0.5 stops: 0.035 − 0.25·b ≤ 0.01
  EXPECT_LE(found.black_level, 0.1 + 1.0 / 256);
  for (const Headroom& h : tried)
    if (h.black_level > 0) {
      EXPECT_EQ(h.exposure_stops, found.exposure_stops);
    }
  // The limit is on one condition's share at both ends together: measured, it decides; else the
  // sum of the two ends' largest shares (perhaps from different conditions) bounds it.
  EXPECT_TRUE((Clipped{0.008, 0.008, 0.009}).within(0.01));
  EXPECT_FALSE((Clipped{0.008, 0.008}).within(0.01));
  // A black level that clips white beyond the limit (more than at the start) ends the search
  // where it stood.
  auto spoils = [](const Headroom& h) {
    return Clipped{h.black_level > 0.01 ? 0.05 : 0.0, 0.03 - 0.1 * h.black_level};
  };
  EXPECT_EQ(find_headroom(spoils, 0.01).black_level, 0.0);
}

// The lit cube with some of its text replaced, as a set over λ = 0, 1.5, 3 under one method,
// made without and with headroom.
struct HeadroomSets {
  size_t failed_without = 0, failed_with = 0;
  std::set<std::pair<double, double>> changes;  // (exposure_stops, black_level) over the entries
};

HeadroomSets make_sets(const std::vector<std::pair<std::string, std::string>>& replaced,
                       const std::string& method) {
  testing::TempDir dir;
  std::string scene = testing::kLitCubeScene;
  for (const auto& [from, to] : replaced) scene.replace(scene.find(from), from.size(), to);
  testing::write_file(dir / "cube.json", scene);
  GenerateOptions options;
  HeadroomSets sets;
  for (bool headroom : {false, true}) {
    const std::string name = headroom ? "room" : "full";
    const Experiment e = load_experiment(testing::write_file(dir / (name + ".json"), R"({
      "version": 1, "name": "room", "seed": 5, "lambda": {"min": 0, "max": 3, "step": 1.5},
      "scenes": [{"name": "cube", "file": "cube.json", "width": 96, "height": 72}],
      "methods": [)" + method + R"(], "audit": {"max_drift": 100, "max_clipped": 0.01},
      "headroom": )" + (headroom ? "true" : "false") + "}"));
    generate_stimulus_set(e, dir / name, options);
    const size_t failed =
        testing::failed_checks(audit_stimulus_set(dir / name / "manifest.json"), "clipped pixels");
    (headroom ? sets.failed_with : sets.failed_without) = failed;
    if (!headroom) continue;
    for (const auto& entry : read_manifest(dir / name / "manifest.json").stimuli)
      sets.changes.insert({entry.extra.at("exposure_stops").get<double>(),
                           entry.extra.at("black_level").get<double>()});
  }
  return sets;
}

// A bright cube under usm3d up to λ = 3: the top of the grid clips more than 1 % of the image
// without headroom, and not with it; every entry records the one exposure used, and no black level
// (nothing clips at black).
TEST(Headroom, ASetWithHeadroomPassesTheClippingCheck) {
  // Bright all over (strong ambient light), so that what clips, clips at white.
  const HeadroomSets sets = make_sets(
      {{"\"irradiance\": 1.6", "\"irradiance\": 2.0"}, {"\"radiance\": 0.25", "\"radiance\": 1.2"}},
      R"({"method": "usm3d", "sigma_fraction": [0.1]})");
  EXPECT_EQ(sets.failed_without, 1u);
  EXPECT_EQ(sets.failed_with, 0u);
  ASSERT_EQ(sets.changes.size(), 1u);
  EXPECT_LT(sets.changes.begin()->first, 0.0);
  EXPECT_EQ(sets.changes.begin()->second, 0.0);
}

// The cube lit from below, its visible faces near black but for ambient light: usm2d's dark
// halos at λ = 3 clip a fifth of the image at black. Headroom lowers the exposure for the white
// the halos also clip, then lifts the black level until the set passes.
TEST(Headroom, ADarkSetPassesWithABlackLevel) {
  const HeadroomSets sets = make_sets({{"\"radiance\": 0.25", "\"radiance\": 0.02"},
                                       {"\"background\": 0.18", "\"background\": 0.01"}},
                                      R"({"method": "usm2d", "sigma_percent": [4]})");
  EXPECT_EQ(sets.failed_without, 1u);
  EXPECT_EQ(sets.failed_with, 0u);
  ASSERT_EQ(sets.changes.size(), 1u);
  EXPECT_LT(sets.changes.begin()->first, 0.0);
  EXPECT_GT(sets.changes.begin()->second, 0.0);
  EXPECT_LT(sets.changes.begin()->second, 0.1);
}

TEST(Headroom, SequencesAreRefused) {
  testing::TempDir dir;
  testing::write_file(dir / "orbit.json", testing::kOrbitingBoxScene);
  const auto file = testing::write_file(dir / "e.json", R"({
    "version": 1, "name": "s", "headroom": true, "lambda": {"min": 0, "max": 1, "step": 1},
    "scenes": [{"name": "orbit", "file": "orbit.json", "frames": "all"}],
    "methods": [{"method": "usm2d", "sigma_percent": [2]}]})");
  EXPECT_NE(testing::input_error_of([&] { load_experiment(file); }).find("still scenes only"),
            std::string::npos);
}

}  // namespace
}  // namespace countershade
