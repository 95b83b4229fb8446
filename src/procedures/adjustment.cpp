// The adjustment procedure (docs/adjustment-study.md): its block of the experiment file, read
// through the parameter bag, and its record.

#include "core/error.h"
#include "core/json_reader.h"
#include "core/parameters.h"
#include "procedures/adjustment_block.h"
#include "procedures/procedure.h"

namespace countershade::procedures {

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

// The one parser of the adjust block.
StudyConfig read_adjustment(const ParameterBag& bag) {
  StudyConfig c;
  if (bag.given("seed")) c.seed = uint64_t(bag.integer_in("seed", 1, 0, 1ll << 53));
  c.plan.repetitions = int(bag.integer_in("repetitions", 1, 1, 100));
  const std::string side =
      bag.choice("side", "counterbalanced", {"counterbalanced", "left", "right"});
  c.plan.side = side == "left" ? Side::left : side == "right" ? Side::right : Side::counterbalanced;
  c.plan.start = bag.choice("start", "random", {"random", "zero"}) == "zero" ? StartMode::zero
                                                                             : StartMode::random;
  c.plan.practice_trials = int(bag.integer_in("practice_trials", 0, 0, 100));
  c.conditions = read_condition_selections(bag, "conditions");
  c.practice_conditions = read_condition_selections(bag, "practice_conditions");
  if (const auto r = bag.structured("repeat")) read_repeat(r->object(), c.timing);
  c.surround = int(bag.integer_in("surround", 128, 0, 255));
  c.gap_px = int(bag.integer_in("gap_px", 48, 0, 4096));
  c.font_px = bag.number_in("font_px", 22, 8, 96);
  if (const auto t = bag.structured("instructions")) read_instructions(t->object(), c.text);
  bag.finish("the adjust block");
  return c;
}

// The adjustment procedure's settings: the study's plan, keys and texts. Its state machine is the
// adjust app's loop (src/adjust/procedure.h), because its input is the participant's keys: one plan
// of trials for the whole study, three adjusted answers per trial, and no per-condition λ to
// choose.
class AdjustmentSettings final : public ProcedureSettings {
 public:
  explicit AdjustmentSettings(StudyConfig config) : config_(std::move(config)) {}
  std::unique_ptr<Procedure> start(const Grid&, uint64_t, const std::string& where) const override {
    throw_input_error(where,
                      "the adjustment procedure runs as the adjust block, not per condition");
  }
  Replay replay(const std::vector<bool>&, const std::string& where) const override {
    throw_input_error(where,
                      "the adjustment procedure's answers are chosen λ, not correct or incorrect; "
                      "there is nothing to replay");
  }

 private:
  StudyConfig config_;
};

class AdjustmentType final : public ProcedureType {
 public:
  std::string name() const override { return "adjustment"; }
  std::string summary() const override {
    return "Method of adjustment: the participant sets λ_Low, λ_High and λ_Best with the arrow "
           "keys, for every condition and repetition in a seeded order (the experiment's adjust "
           "block)";
  }
  Study study() const override { return Study::adjustment; }
  std::vector<ParameterDoc> parameter_docs() const override {
    return {
        {"repetitions", "1", "Times each condition is shown, 1 to 100"},
        {"side", "counterbalanced",
         "Side of the enhanced image: counterbalanced, left or right. Counterbalanced alternates "
         "a condition's side over its repetitions and balances the first side across conditions"},
        {"start", "random", "Start index of each question: random (seeded) or zero"},
        {"practice_trials", "0",
         "Trials before the study, drawn from the practice conditions; their answers go to the "
         "trajectory log only"},
        {"practice_conditions", "",
         "The conditions practice trials show, as conditions lists them. Absent: every condition "
         "whose images change with λ (a control that never changes teaches nothing; a study where "
         "none changes refuses practice trials)"},
        {"seed", "",
         "Base seed; each session's seed mixes it with the subject id and session number. Absent: "
         "the set's seed"},
        {"conditions", "",
         "The conditions to run, [{\"scene\", \"method\", \"sigma\"}, …] (method is the set's "
         "folder label, e.g. depth-usm-darken). Absent: all"},
        {"repeat", "",
         "Auto-repeat of a held arrow key: {\"delay_ms\": 400, \"interval_ms\": 100} (the "
         "defaults)"},
        {"surround", "128", "Grey level of the background, 0 to 255"},
        {"gap_px", "48", "Space between the two images, pixels"},
        {"font_px", "22", "Text size, pixels"},
        {"instructions", "",
         "Texts to replace (English by default): any of welcome, resume, practice, practice_done, "
         "low, high, best, keys, paused, finished"},
    };
  }
  std::shared_ptr<const ProcedureSettings> parse(const ParameterBag& bag) const override {
    return std::make_shared<AdjustmentSettings>(read_adjustment(bag));
  }
};

}  // namespace

std::unique_ptr<const ProcedureType> make_adjustment_procedure() {
  return std::make_unique<AdjustmentType>();
}

StudyConfig parse_study_config(const nlohmann::json& value, const std::string& file,
                               const std::string& path) {
  return read_adjustment(ParameterBag::from_json(value, file, path));
}

}  // namespace countershade::procedures
