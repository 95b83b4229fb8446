// Headroom against clipping (an experiment's "headroom"): the search for the exposure, and a set
// that clips at the top of its grid without it and passes the audit's clipping check with it.

#include "stimuli/headroom.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "core/error.h"
#include "formats/manifest.h"
#include "stimuli/audit.h"
#include "stimuli/experiment.h"
#include "stimuli/stimulus_set.h"
#include "set_test_util.h"
#include "test_util.h"

namespace countershade {
namespace {

namespace fs = std::filesystem;

TEST(Headroom, TheSearchFindsTheExposureClosestToZeroWithinTheLimit) {
  // White clipping that falls linearly as the exposure drops: within 0.01 from −1.0 stops down.
  int calls = 0;
  auto linear = [&](double stops) {
    ++calls;
    return Clipped{std::max(0.0, 0.05 + 0.04 * stops), 0.0};
  };
  const double stops = headroom_stops(linear, 0.01);
  EXPECT_LE(stops, -1.0);
  EXPECT_GE(stops, -1.05);
  EXPECT_LE(calls, 10);
  // Already within the limit: no change, one look.
  calls = 0;
  EXPECT_EQ(headroom_stops([&](double) { return ++calls, Clipped{0.005, 0.004}; }, 0.01), 0.0);
  EXPECT_EQ(calls, 1);
  // A share that does not fall with the exposure: no change is worth making.
  EXPECT_EQ(headroom_stops([](double) { return Clipped{0.2, 0.0}; }, 0.01), 0.0);
  EXPECT_EQ(headroom_stops([](double) { return Clipped{0.0, 0.2}; }, 0.01), 0.0);
  // One that falls but never far enough: the floor's neighbour, where it gave up.
  EXPECT_EQ(headroom_stops([](double stops) { return Clipped{0.5 + 0.01 * stops, 0.0}; }, 0.01, 0.05, -2), -1.0);
  // Black clipping that falls as the exposure rises: within 0.01 from +0.6 stops up.
  const double up = headroom_stops([](double stops) { return Clipped{0.0, std::max(0.0, 0.016 - 0.01 * stops)}; }, 0.01);
  EXPECT_GE(up, 0.6);
  EXPECT_LE(up, 0.65);
  // Going down against white clipping must not clip black instead: the search stops at the first
  // step that puts black over the limit, without going deeper (dark renders are the dearest).
  calls = 0;
  EXPECT_EQ(headroom_stops([&](double stops) { return ++calls, Clipped{0.02 + 0.02 * stops, 0.005 - 0.04 * stops}; }, 0.01),
            0.0);
  EXPECT_EQ(calls, 2);
  // Both ends over the limit: no exposure helps one without the other.
  EXPECT_EQ(headroom_stops([](double stops) { return Clipped{0.02 + stops, 0.02 - stops}; }, 0.01), 0.0);
}

// A bright cube under usm3d up to λ = 3: the top of the grid clips more than 1 % of the image
// without headroom, and not with it; every entry records the one exposure used.
TEST(Headroom, ASetWithHeadroomPassesTheClippingCheck) {
  testing::TempDir dir;
  std::string scene = testing::kLitCubeScene;
  // Bright all over (strong ambient light), so that what clips, clips at white.
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"\"irradiance\": 1.6", "\"irradiance\": 2.0"},
                                 {"\"radiance\": 0.25", "\"radiance\": 1.2"}})
    scene.replace(scene.find(from), from.size(), to);
  testing::write_file(dir / "cube.json", scene);
  auto experiment = [&](bool headroom) {
    return load_experiment(testing::write_file(dir / (headroom ? "room.json" : "full.json"), std::string(R"({
      "version": 1, "name": "room", "seed": 5, "lambda": {"min": 0, "max": 3, "step": 1.5},
      "scenes": [{"name": "cube", "file": "cube.json", "width": 96, "height": 72}],
      "methods": [{"method": "usm3d", "sigma_fraction": [0.1]}], "audit": {"max_drift": 100, "max_clipped": 0.01})") +
                                                   (headroom ? R"(, "headroom": true})" : "}")));
  };
  GenerateOptions options;
  options.contact_sheets = false;
  for (bool headroom : {false, true}) {
    const fs::path set = dir / (headroom ? "room" : "full");
    generate_stimulus_set(experiment(headroom), set, options);
    const AuditReport report = audit_stimulus_set(set / "manifest.json");
    const size_t failed = testing::failed_checks(report, "clipped pixels");
    EXPECT_EQ(failed, headroom ? 0u : 1u) << (headroom ? "with headroom" : "without");
    if (!headroom) continue;
    std::set<double> stops;
    for (const auto& entry : read_manifest(set / "manifest.json").stimuli) stops.insert(entry.extra.at("exposure_stops").get<double>());
    ASSERT_EQ(stops.size(), 1u);
    EXPECT_LT(*stops.begin(), 0.0);
  }
}

TEST(Headroom, SequencesAreRefused) {
  testing::TempDir dir;
  testing::write_file(dir / "orbit.json", testing::kOrbitingBoxScene);
  const auto file = testing::write_file(dir / "e.json", R"({
    "version": 1, "name": "s", "headroom": true, "lambda": {"min": 0, "max": 1, "step": 1},
    "scenes": [{"name": "orbit", "file": "orbit.json", "frames": "all"}],
    "methods": [{"method": "usm2d", "sigma_percent": [2]}]})");
  EXPECT_NE(testing::input_error_of([&] { load_experiment(file); }).find("still scenes only"), std::string::npos);
}

}  // namespace
}  // namespace countershade
