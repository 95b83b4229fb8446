#include "procedures/adjustment_block.h"

#include "core/error.h"
#include "core/json_reader.h"

namespace countershade::procedures {

const char* side_name(Side side) {
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

nlohmann::ordered_json StudyConfig::to_json() const {
  nlohmann::ordered_json j;
  j["seed"] = seed ? nlohmann::ordered_json(*seed) : nlohmann::ordered_json("manifest");
  j["repetitions"] = plan.repetitions;
  j["side"] = side_name(plan.side);
  j["start"] = plan.start == StartMode::random ? "random" : "zero";
  j["practice_trials"] = plan.practice_trials;
  auto& c = j["conditions"] = nlohmann::ordered_json::array();
  for (const auto& s : conditions)
    c.push_back({{"scene", s.scene}, {"method", s.method}, {"sigma", s.sigma}});
  if (!practice_conditions
           .empty()) {  // only when named, so the record of older sessions stays the same
    auto& p = j["practice_conditions"] = nlohmann::ordered_json::array();
    for (const auto& s : practice_conditions)
      p.push_back({{"scene", s.scene}, {"method", s.method}, {"sigma", s.sigma}});
  }
  j["repeat"] = {{"delay_ms", timing.repeat_delay_s * 1000},
                 {"interval_ms", timing.repeat_interval_s * 1000}};
  j["surround"] = surround;
  j["gap_px"] = gap_px;
  j["font_px"] = font_px;
  j["instructions"] = {{"welcome", text.welcome},   {"resume", text.resume},
                       {"practice", text.practice}, {"practice_done", text.practice_done},
                       {"low", text.questions[0]},  {"high", text.questions[1]},
                       {"best", text.questions[2]}, {"keys", text.keys_hint},
                       {"paused", text.paused},     {"finished", text.finished}};
  return j;
}

namespace {

// The texts a study may override; the rest keep their defaults.
void read_instructions(const JsonObject& t, Instructions& x) {
  x.welcome = t.string_or("welcome", x.welcome);
  x.resume = t.string_or("resume", x.resume);
  x.practice = t.string_or("practice", x.practice);
  x.practice_done = t.string_or("practice_done", x.practice_done);
  x.questions[0] = t.string_or("low", x.questions[0]);
  x.questions[1] = t.string_or("high", x.questions[1]);
  x.questions[2] = t.string_or("best", x.questions[2]);
  x.keys_hint = t.string_or("keys", x.keys_hint);
  x.paused = t.string_or("paused", x.paused);
  x.finished = t.string_or("finished", x.finished);
  t.finish();
}

void read_repeat(const JsonObject& r, RepeatTiming& timing) {
  timing.repeat_delay_s = r.number_in("delay_ms", 400, 50, 5000) / 1000;
  timing.repeat_interval_s = r.number_in("interval_ms", 100, 16, 2000) / 1000;
  r.finish();
}

}  // namespace

StudyConfig parse_study_config(const nlohmann::json& value, const std::string& file,
                               const std::string& path) {
  StudyConfig c;
  JsonObject o(value, file, path);
  if (o.has("seed")) c.seed = uint64_t(o.integer_in("seed", 1, 0, 1ll << 53));
  c.plan.repetitions = int(o.integer_in("repetitions", 1, 1, 100));
  const std::string side =
      o.choice("side", "counterbalanced", {"counterbalanced", "left", "right"});
  c.plan.side = side == "left" ? Side::left : side == "right" ? Side::right : Side::counterbalanced;
  c.plan.start = o.choice("start", "random", {"random", "zero"}) == "zero" ? StartMode::zero
                                                                           : StartMode::random;
  c.plan.practice_trials = int(o.integer_in("practice_trials", 0, 0, 100));
  c.conditions = read_condition_selections(o, "conditions");
  c.practice_conditions = read_condition_selections(o, "practice_conditions");
  if (o.has("repeat")) read_repeat(o.object("repeat"), c.timing);
  c.surround = int(o.integer_in("surround", 128, 0, 255));
  c.gap_px = int(o.integer_in("gap_px", 48, 0, 4096));
  c.font_px = o.number_in("font_px", 22, 8, 96);
  if (o.has("instructions")) read_instructions(o.object("instructions"), c.text);
  o.finish();
  return c;
}

}  // namespace countershade::procedures
