#include "procedures/choice_block.h"

#include "core/error.h"
#include "core/json_reader.h"
#include "core/number_format.h"

namespace countershade::procedures {

const char* layout_name(Layout layout) {
  return layout == Layout::spatial ? "spatial" : "temporal";
}

// The "condition_procedures" list: each entry a condition ({scene, method, sigma}) and its
// "procedure"; a condition named twice is refused, as its procedure would be ambiguous.
std::vector<ConditionProcedureBlock> read_condition_procedures(const JsonObject& block,
                                                               const std::string& file) {
  std::vector<ConditionProcedureBlock> out;
  if (!block.has("condition_procedures")) return out;
  for (const JsonObject& entry : block.objects("condition_procedures")) {
    ConditionProcedureBlock c;
    c.condition = {entry.string("scene"), entry.string("method"), entry.number("sigma")};
    entry.object("procedure");  // required, and an object
    const nlohmann::json& procedure = entry.raw("procedure");
    c.where = file + ": " + entry.key_path("procedure");
    c.procedure = read_procedure_block(procedure, file, entry.key_path("procedure"));
    entry.finish();
    for (const auto& earlier : out)
      if (earlier.condition.names(c.condition.scene, c.condition.method, c.condition.sigma))
        throw_input_error(file + ": " + entry.key_path("scene"),
                          "the condition " + c.condition.scene + " / " + c.condition.method +
                              " / σ " + format_value(c.condition.sigma) + " is listed twice");
    c.source = {{"scene", c.condition.scene},
                {"method", c.condition.method},
                {"sigma", c.condition.sigma},
                {"procedure", nlohmann::ordered_json(procedure)}};
    out.push_back(std::move(c));
  }
  return out;
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
  c.condition_procedures = read_condition_procedures(o, file);
  o.finish();
  return c;
}

const ConditionProcedureBlock* ChoiceConfig::own_procedure(const std::string& scene,
                                                           const std::string& method,
                                                           double sigma) const {
  for (const auto& c : condition_procedures)
    if (c.condition.names(scene, method, sigma)) return &c;
  return nullptr;
}

const ProcedureBlock& ChoiceConfig::procedure_of(const std::string& scene,
                                                 const std::string& method, double sigma) const {
  const auto* own = own_procedure(scene, method, sigma);
  return own ? own->procedure : procedure;
}

std::string ChoiceConfig::procedure_source_of(const std::string& scene, const std::string& method,
                                              double sigma) const {
  const auto* own = own_procedure(scene, method, sigma);
  return own ? own->where : source + "procedure";
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
  if (!condition_procedures.empty()) {
    // Only when given, so that the record of a session without them reads as before.
    auto& list = j["condition_procedures"] = nlohmann::ordered_json::array();
    for (const auto& c : condition_procedures) list.push_back(c.source);
  }
  if (seed) j["seed"] = *seed;
  return j;
}

}  // namespace countershade::procedures
