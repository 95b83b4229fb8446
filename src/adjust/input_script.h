#pragma once
// Key input that does not come from a person: a timed key script (--script) and a simulated
// observer with known thresholds (--observer simulated:SEED). Both produce the same events the
// window's key callback produces, so tests exercise the real session loop.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "adjust/procedure.h"
#include "adjust/study.h"

namespace countershade::adjust {

struct InputEvent {
  enum class Kind { press, release, screenshot, close };
  double time_s = 0;  // since the first frame after preloading
  Kind kind = Kind::press;
  Key key = Key::enter;
};

// Reads a key script. Each line is "<delay_ms> <action>", the delay counted from the previous
// line; '#' starts a comment. Actions: up, down, left, right, enter, backspace, escape, q (a press
// and a release 20 ms later); "hold KEY MS" (a key held for MS ms, which auto-repeats);
// "screenshot"; "close" (the window's close button). Throws InputError naming the line.
std::vector<InputEvent> parse_key_script(const std::filesystem::path& path);
std::vector<InputEvent> parse_key_script_text(const std::string& text, const std::string& file);

// Key names for scripts and the trajectory log.
const char* key_name(Key key);
std::optional<Key> key_from_name(const std::string& name);

// A model observer: for every condition it has latent thresholds for the three questions, drawn
// from the seed, and answers with the first grid index at or above them. It is deterministic
// given the seed, so tests know every answer in advance.
class SimulatedObserver {
 public:
  SimulatedObserver(uint64_t seed, const Study& study, double step_interval_s = 0.02);

  // The latent λ of a question for a condition and repetition, and the grid index answered.
  double latent_lambda(int condition, int repetition, Question question) const;
  int answer_index(int condition, int repetition, Question question) const;

  // The observer's next key events, given what is on screen now.
  std::vector<InputEvent> act(const Procedure& procedure, double time_s);

 private:
  uint64_t seed_;
  const Study& study_;
  double interval_s_;
  double next_action_s_ = 0;
};

// Parses "simulated:SEED"; throws InputError for anything else.
uint64_t parse_observer_spec(const std::string& spec);

}  // namespace countershade::adjust
