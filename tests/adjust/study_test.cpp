// Loading a study from a stimulus set, its configuration, key scripts and the simulated observer.

#include "runtime/study.h"

#include <gtest/gtest.h>

#include <set>

#include "adjust/simulated_observer.h"
#include "runtime/key_script.h"
#include "stimuli/set_test_util.h"
#include "tiny_set.h"

namespace countershade::adjust {

// From the study runtime (src/runtime).
using runtime::check_subject_id;
using runtime::InputEvent;
using runtime::load_study;
using runtime::parse_key_script_text;
using runtime::session_seed;
using runtime::Stimulus;
using runtime::Study;
using runtime::verify_study_images;
namespace {

namespace fs = std::filesystem;

TEST(AdjustStudy, ConditionsAreEverySceneMethodSigmaWithTheReferenceAtIndexZero) {
  testing::TempDir dir;
  Study study = load_study(testing::make_tiny_set(dir), std::nullopt);
  ASSERT_EQ(study.conditions.size(), 4u);  // 2 scenes × 2 σ
  std::set<std::string> names;
  for (size_t c = 0; c < study.conditions.size(); ++c) {
    const Condition& k = study.conditions[c];
    names.insert(k.scene + "/" + k.method + "/" + format_value(k.sigma));
    EXPECT_EQ(k.grid_size, 6);  // λ = 0, 0.4, ..., 2
    const auto& images = study.condition_images[c];
    ASSERT_EQ(images.size(), 7u);
    EXPECT_EQ(study.image_of(images[0]).relative, k.scene + "/reference.png");
    // λ = 0 is the identity: the set's λ = 0 image is the reference, byte for byte.
    EXPECT_EQ(study.image_of(images[1]).relative,
              k.scene + "/usm3d/sigma-" + format_value(k.sigma) + "/lambda-0.png");
    EXPECT_EQ(study.image_of(images[1]).sha256, study.image_of(images[0]).sha256);
    EXPECT_EQ(study.image_of(images[6]).relative,
              k.scene + "/usm3d/sigma-" + format_value(k.sigma) + "/lambda-2.png");
  }
  EXPECT_EQ(names, (std::set<std::string>{"front/usm3d/0.03", "front/usm3d/0.08",
                                          "small/usm3d/0.03", "small/usm3d/0.08"}));
  EXPECT_DOUBLE_EQ(study.lambda(3), 1.2);
  EXPECT_EQ(study.max_width(), 96);
  EXPECT_EQ(study.max_height(), 72);
  EXPECT_EQ(study.config_source, "defaults");
  EXPECT_NO_THROW(verify_study_images(study));
}

TEST(AdjustStudy, ConfigurationFromTheExperimentSelectsConditionsAndSettings) {
  testing::TempDir dir;
  Study study =
      load_study(testing::make_tiny_set(dir, R"({"repetitions": 3, "side": "left", "start": "zero",
      "conditions": [{"scene": "small", "method": "usm3d", "sigma": 0.08}],
      "instructions": {"low": "Wann sehen Sie einen Unterschied?"}, "repeat": {"delay_ms": 300, "interval_ms": 50}})"),
                 std::nullopt);
  ASSERT_EQ(study.conditions.size(), 1u);
  EXPECT_EQ(study.conditions[0].scene, "small");
  EXPECT_EQ(study.config.plan.repetitions, 3);
  EXPECT_EQ(study.config.plan.side, Side::left);
  EXPECT_EQ(study.config.plan.start, StartMode::zero);
  EXPECT_EQ(study.config.text.questions[0], "Wann sehen Sie einen Unterschied?");
  EXPECT_DOUBLE_EQ(study.config.timing.repeat_interval_s, 0.05);
  EXPECT_EQ(study.config_source, "experiment.adjust");
}

TEST(AdjustStudy, BadConfigurationsAndSetsAreOneLineErrors) {
  testing::TempDir dir;
  fs::path manifest = testing::make_tiny_set(dir);
  struct Case {
    std::string config, expected;
  } cases[] = {
      {R"({"repetitions": 0})", "repetitions"},
      {R"({"side": "top"})", "side"},
      {R"({"conditions": [{"scene": "front", "method": "usm3d", "sigma": 0.5}]})",
       "no condition scene 'front'"},
      {R"({"instructions": {"lo": "typo"}})", "instructions.lo"},
      {R"({"surround": 300})", "surround"},
  };
  for (const auto& c : cases) {
    fs::path file = testing::write_file(dir / "procedure.json", c.config);
    std::string message = testing::input_error_of([&] { load_study(manifest, file); });
    EXPECT_NE(message.find(c.expected), std::string::npos) << c.config << " -> " << message;
    EXPECT_NE(message.find("procedure.json"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos);
  }
  // A set with a hole in a λ grid cannot be adjusted.
  std::string text = testing::read_file(manifest);
  auto at = text.find("\"lambda_index\": 3");
  ASSERT_NE(at, std::string::npos);
  testing::write_file(dir / "set/holey.json", text.replace(at, 17, "\"lambda_index\": 9"));
  EXPECT_NE(testing::input_error_of([&] {
              load_study(dir / "set/holey.json", std::nullopt);
            }).find("outside the λ grid"),
            std::string::npos);
}

TEST(AdjustStudy, ChangedOrMissingImagesAreFoundBeforeTheSessionStarts) {
  testing::TempDir dir;
  fs::path manifest = testing::make_tiny_set(dir);
  Study study = load_study(manifest, std::nullopt);
  fs::path changed = dir / "set/front/usm3d/sigma-0.03/lambda-1.2.png";
  std::string bytes = testing::read_file(changed);
  bytes[bytes.size() / 2] ^= 1;
  testing::write_file(changed, bytes);
  std::string message = testing::input_error_of([&] { verify_study_images(study); });
  EXPECT_NE(message.find("lambda-1.2.png: sha256 does not match"), std::string::npos) << message;
  fs::remove(changed);
  message = testing::input_error_of([&] { verify_study_images(study); });
  EXPECT_NE(message.find("lambda-1.2.png: missing image"), std::string::npos) << message;
}

TEST(AdjustStudy, ASequenceIsAStimulusOfFramesLoopedOnTheSessionClock) {
  testing::TempDir dir;
  const fs::path manifest = testing::make_sequence_set(dir);
  const Study study = load_study(manifest, std::nullopt);
  ASSERT_EQ(study.conditions.size(), 1u);
  const auto& slots = study.condition_images[0];
  ASSERT_EQ(slots.size(), 3u);  // the reference and λ = 0, 1
  EXPECT_EQ(study.images.size(), 3u * 4);
  for (size_t slot = 0; slot < slots.size(); ++slot) {
    const Stimulus& s = study.stimuli[size_t(slots[slot])];
    ASSERT_EQ(s.frames.size(), 4u);
    EXPECT_EQ(s.fps, 4.0);
    EXPECT_EQ(s.sequence, slot == 0 ? "orbit/reference"
                                    : "orbit/usm2d/sigma-2/lambda-" + std::to_string(slot - 1));
    for (int f = 0; f < 4; ++f)
      EXPECT_EQ(study.images[size_t(s.frames[size_t(f)])].relative,
                s.sequence + "/frame-000" + std::to_string(f) + ".png");
    // Frame k shows during [k/4, (k+1)/4) s of every second: the same on every side and every λ.
    EXPECT_EQ(s.frame_at(0.0), s.frames[0]);
    EXPECT_EQ(s.frame_at(0.26), s.frames[1]);
    EXPECT_EQ(s.frame_at(0.99), s.frames[3]);
    EXPECT_EQ(s.frame_at(1.0), s.frames[0]);  // it loops
    EXPECT_EQ(s.frame_at(7.6), s.frames[2]);
  }
  // A sequence that lacks a frame cannot play in step with its reference.
  OrderedJson m = testing::manifest_json(manifest.parent_path());
  auto& stimuli = m["stimuli"];
  for (size_t i = 0; i < stimuli.size(); ++i)
    if (stimuli[i]["file"] == "orbit/usm2d/sigma-2/lambda-1/frame-0002.png") stimuli.erase(i);
  testing::write_file(dir / "set/short.json", m.dump());
  const std::string message =
      testing::input_error_of([&] { load_study(dir / "set/short.json", std::nullopt); });
  EXPECT_NE(message.find("has 3 frames, its reference 4"), std::string::npos) << message;
  // Nor one that lists a frame twice.
  m = testing::manifest_json(manifest.parent_path());
  for (auto& s : m["stimuli"])
    if (s["file"] == "orbit/usm2d/sigma-2/lambda-1/frame-0002.png") s["frame"] = 1;
  testing::write_file(dir / "set/twice.json", m.dump());
  const std::string twice =
      testing::input_error_of([&] { load_study(dir / "set/twice.json", std::nullopt); });
  EXPECT_NE(twice.find("frame 1 of"), std::string::npos) << twice;
  EXPECT_NE(twice.find("listed twice"), std::string::npos) << twice;
}

TEST(AdjustStudy, SubjectIdsMustBePlainFileNames) {
  for (const char* good : {"P01", "anna_k", "s-7"}) EXPECT_NO_THROW(check_subject_id(good));
  for (const char* bad : {"", "../x", "a/b", "a b", "P01.csv", "x\\y"})
    EXPECT_NE(testing::input_error_of([&] { check_subject_id(bad); }).find("--subject"),
              std::string::npos)
        << bad;
  EXPECT_NE(session_seed(1, "P01", 1), session_seed(1, "P02", 1));
  EXPECT_NE(session_seed(1, "P01", 1), session_seed(1, "P01", 2));
  EXPECT_EQ(session_seed(1, "P01", 1), session_seed(1, "P01", 1));
}

TEST(AdjustScript, TimesAccumulateAndHoldsBecomePressAndRelease) {
  auto events = parse_key_script_text(
      "# start\n500 enter\n100 right  # one step\n0 hold up 1200\n250 screenshot\n10 close\n",
      "keys.txt");
  ASSERT_EQ(events.size(), 8u);
  EXPECT_DOUBLE_EQ(events[0].time_s, 0.5);
  EXPECT_EQ(events[0].kind, InputEvent::Kind::press);
  EXPECT_EQ(events[0].key, Key::enter);
  EXPECT_NEAR(events[1].time_s, 0.52, 1e-12);
  EXPECT_EQ(events[1].kind, InputEvent::Kind::release);
  EXPECT_NEAR(events[2].time_s, 0.6, 1e-12);
  EXPECT_EQ(events[2].key, Key::right);
  // The hold starts at 0.6 s too; its release at 1.8 s comes after the screenshot at 0.85 s.
  EXPECT_EQ(events[3].key, Key::up);
  EXPECT_EQ(events[3].kind, InputEvent::Kind::press);
  EXPECT_EQ(events[4].kind, InputEvent::Kind::release);
  EXPECT_EQ(events[4].key, Key::right);
  EXPECT_EQ(events[5].kind, InputEvent::Kind::screenshot);
  EXPECT_NEAR(events[5].time_s, 0.85, 1e-12);
  EXPECT_EQ(events[6].kind, InputEvent::Kind::close);
  EXPECT_NEAR(events[7].time_s, 1.8, 1e-12);
  EXPECT_EQ(events[7].kind, InputEvent::Kind::release);

  for (const char* bad :
       {"x enter", "100", "100 jump", "-5 enter", "100 hold up", "100 enter now"}) {
    std::string message = testing::input_error_of(
        [&] { parse_key_script_text(std::string("10 enter\n") + bad, "keys.txt"); });
    EXPECT_NE(message.find("keys.txt: line 2"), std::string::npos) << bad << " -> " << message;
  }
  EXPECT_EQ(parse_observer_spec("simulated:42"), 42u);
  EXPECT_NE(testing::input_error_of([] { parse_observer_spec("human"); }).find("--observer"),
            std::string::npos);
}

TEST(AdjustObserver, AnswersAreTheFirstGridValueAtOrAboveItsLatentThresholds) {
  testing::TempDir dir;
  Study study = load_study(testing::make_tiny_set(dir), std::nullopt);
  SimulatedObserver a(3, study), b(3, study);
  int ordered = 0;
  for (int c = 0; c < 4; ++c)
    for (int r = 1; r <= 3; ++r) {
      double low = a.latent_lambda(c, r, Question::low),
             high = a.latent_lambda(c, r, Question::high);
      ordered += low < high;
      for (Question q : {Question::low, Question::high, Question::best}) {
        int index = a.answer_index(c, r, q);
        EXPECT_EQ(index, b.answer_index(c, r, q));
        double latent = a.latent_lambda(c, r, q);
        EXPECT_TRUE(study.lambda(index) >= latent || index == 5);
        if (index > 0) {
          EXPECT_LT(study.lambda(index - 1), latent);
        }
      }
    }
  EXPECT_EQ(ordered, 12);
}

}  // namespace
}  // namespace countershade::adjust

namespace countershade::adjust {
namespace {

// A set with one enhanced condition and one whose images never change (method "none").
std::filesystem::path make_set_with_control(const testing::TempDir& dir,
                                            const std::string& adjust) {
  testing::write_file(dir / "cube.json", testing::kLitCubeScene);
  testing::write_file(dir / "experiment.json", R"({"version": 1, "name": "control", "seed": 3,
      "lambda": {"min": 0, "max": 1, "step": 0.5},
      "scenes": [{"name": "front", "file": "cube.json", "width": 48, "height": 36}],
      "methods": [{"method": "usm3d", "sigma_fraction": [0.05]}, {"method": "none"}],
      "adjust": )" + adjust + "}");
  GenerateOptions options;
  generate_stimulus_set(load_experiment(dir / "experiment.json"), dir / "set", options);
  return dir / "set" / "manifest.json";
}

// Practice shows only conditions whose images change with λ, unless the experiment names others;
// a study with nothing to practise on refuses practice trials.
TEST(AdjustStudy, PracticeNeverShowsAConditionWhoseImagesDoNotChange) {
  testing::TempDir dir;
  const Study study =
      load_study(make_set_with_control(dir, R"({"practice_trials": 6})"), std::nullopt);
  ASSERT_EQ(study.conditions.size(), 2u);
  int control = -1;
  for (int c = 0; c < 2; ++c)
    if (!study.changes_with_lambda(c)) control = c;
  ASSERT_GE(control, 0) << "the none method's images equal the reference";
  PlanSettings settings = study.config.plan;
  const auto plan = plan_trials(study.conditions, settings);
  int practice = 0;
  for (const Trial& t : plan)
    if (t.practice) {
      ++practice;
      EXPECT_NE(t.condition, control);
    }
  EXPECT_EQ(practice, 6);

  testing::TempDir named;
  const Study chosen = load_study(
      make_set_with_control(
          named,
          R"({"practice_trials": 2, "practice_conditions": [{"scene": "front", "method": "none", "sigma": 0}]})"),
      std::nullopt);
  for (const Trial& t : plan_trials(chosen.conditions, chosen.config.plan)) {
    if (!t.practice) continue;
    EXPECT_FALSE(chosen.changes_with_lambda(t.condition));
  }
}

}  // namespace
}  // namespace countershade::adjust
