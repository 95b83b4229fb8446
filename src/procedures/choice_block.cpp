#include "procedures/choice_block.h"

#include "core/error.h"
#include "core/json_reader.h"

namespace countershade::procedures {

const char* layout_name(Layout layout) {
  return layout == Layout::spatial ? "spatial" : "temporal";
}

ChoiceConfig parse_choice_config(const nlohmann::json& value, const std::string& file,
                                 const std::string& path) {
  if (!value.is_object())
    throw_input_error(file + (path.empty() ? "" : ": " + path), "expected a JSON object");
  ChoiceConfig c;
  c.source = file + ": " + (path.empty() ? "" : path + ".");
  JsonObject o(value, file, path);
  c.n_afc = int(o.integer_in("n_afc", 2, 2, 4));
  c.layout = o.choice("layout", "spatial", {"spatial", "temporal"}) == "temporal" ? Layout::temporal
                                                                                  : Layout::spatial;
  c.interval_frames = int(o.integer_in("interval_frames", 30, 1, 6000));
  c.blank_frames = int(o.integer_in("blank_frames", 30, 0, 6000));
  c.feedback_frames = int(o.integer_in("feedback_frames", 0, 0, 600));
  c.question = o.string_or("question", c.question);
  c.welcome = o.string_or("welcome", c.welcome);
  c.max_trials = int(o.integer_in("max_trials", 200, 1, 100000));
  c.conditions = read_condition_selections(o, "conditions");
  c.practice_conditions = read_condition_selections(o, "practice_conditions");
  c.practice_trials = int(o.integer_in("practice_trials", 0, 0, 100));
  if (o.has("seed")) c.seed = uint64_t(o.integer_in("seed", 1, 0, 1ll << 53));
  o.object("procedure");  // required, and an object
  c.procedure_source = o.raw("procedure");
  c.procedure = read_procedure_block(c.procedure_source, file, o.key_path("procedure"));
  o.finish();
  return c;
}

std::string ChoiceConfig::answer_keys() const {
  return n_afc == 2 ? "Left/Right or 1/2" : "1 to " + std::to_string(n_afc);
}

std::string ChoiceConfig::welcome_text() const {
  if (!welcome.empty()) return welcome;
  const std::string n = n_afc == 2 ? "Two" : n_afc == 3 ? "Three" : "Four";
  const std::string shown = layout == Layout::spatial ? "side by side" : "one after the other";
  const std::string keys =
      n_afc == 2
          ? (layout == Layout::spatial ? "Press Left for the left one and Right for the right one"
                                       : "Press Left for the first and Right for the second")
          : "Press its number (1 is the " +
                std::string(layout == Layout::spatial ? "leftmost" : "first") + ")";
  return n + " images of the same scene are shown " + shown + "; one of them is enhanced. " + keys +
         ". Press Esc at any time to pause.\n\nPress Enter to begin.";
}

nlohmann::ordered_json ChoiceConfig::to_json() const {
  nlohmann::ordered_json j = {{"n_afc", n_afc},
                              {"layout", layout_name(layout)},
                              {"interval_frames", interval_frames},
                              {"blank_frames", blank_frames},
                              {"feedback_frames", feedback_frames},
                              {"question", question},
                              {"procedure", procedure_source},
                              {"max_trials", max_trials},
                              {"practice_trials", practice_trials}};
  procedure.settings->describe(j);
  if (seed) j["seed"] = *seed;
  return j;
}

}  // namespace countershade::procedures
