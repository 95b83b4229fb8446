#pragma once
// The adjustment study's block of an experiment file (docs/adjustment-study.md): the plan's
// settings, the key repeat, the layout and the texts. It is read here, apart from the app, so
// that an experiment is checked when its set is made; the app (src/adjust) runs it.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "formats/responses.h"
#include "procedures/condition_selection.h"

namespace countershade::procedures {

// Which side the enhanced image is shown on. `counterbalanced` only appears in the configuration;
// every planned trial has a concrete side.
enum class Side { left, right, counterbalanced };
inline const char* side_name(Side side) {
  switch (side) {
    case Side::left:
      return "left";
    case Side::right:
      return "right";
    case Side::counterbalanced:
      return "counterbalanced";
  }
  return "?";
}

enum class StartMode { random, zero };

struct PlanSettings {
  uint64_t seed = 1;
  int repetitions = 1;
  Side side = Side::counterbalanced;
  StartMode start = StartMode::random;
  int practice_trials = 0;
  // The conditions practice may show (indices); empty: every condition. A study fills it with
  // those whose images change with λ, so practice always has something to find.
  std::vector<int> practice_conditions;
};

// Auto-repeat of a held arrow key.
struct RepeatTiming {
  double repeat_delay_s = 0.40;     // a held arrow key starts repeating after this
  double repeat_interval_s = 0.10;  // then steps at this interval
};

struct Instructions {
  std::string welcome =
      "Two images of the same scene are shown side by side. One of them is enhanced; use the arrow "
      "keys to make the enhancement stronger (Up or Right) or weaker (Down or Left), and press "
      "Enter "
      "to give your answer. There are three questions for each pair. Press Esc at any time to "
      "pause.\n\n"
      "Press Enter to begin.";
  std::string resume =
      "Welcome back. The session continues where it stopped.\n\nPress Enter to continue.";
  std::string practice = "Practice";
  std::string practice_done =
      "The practice trials are over. The study itself begins now.\n\nPress Enter to continue.";
  std::string questions[kQuestionCount] = {
      "When is a difference between the two images first visible?",
      "When is the difference too strong or objectionable?",
      "Which setting gives the best contrast?",
  };
  std::string keys_hint =
      "Up/Right: stronger    Down/Left: weaker    Enter: confirm    Backspace: previous question   "
      " Esc: pause";
  std::string paused = "Paused.\n\nPress Enter to resume, or Q to quit and save.";
  std::string finished = "Thank you. All answers are saved.\n\nPress Enter to close.";
};

struct StudyConfig {
  PlanSettings plan;             // plan.seed is the configured base seed
  std::optional<uint64_t> seed;  // unset: the manifest's seed
  // Conditions to run ({scene, method, sigma}); empty: every condition in the set.
  using Selection = ConditionSelection;
  std::vector<Selection> conditions;
  // Conditions practice trials show; empty: those whose images change with λ.
  std::vector<Selection> practice_conditions;
  Instructions text;
  RepeatTiming timing;
  int surround = 128;  // grey level of the background, 0–255 (display values, no gamma change)
  int gap_px = 48;     // between the two images
  double font_px = 22;

  nlohmann::ordered_json to_json() const;
};

// Reads the procedure configuration: a JSON object (a file of its own, or the "adjust" object of
// an experiment file). `file` and `path` name it in messages.
StudyConfig parse_study_config(const nlohmann::json& value, const std::string& file,
                               const std::string& path);

}  // namespace countershade::procedures
