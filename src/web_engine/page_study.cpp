#include "web_engine/page_study.h"

#include <string>
#include <vector>

namespace countershade::web_engine {
namespace {

using nlohmann::json;

// One still per image: the reference, then each λ index's image, with their hashes.
void add_condition_images(runtime::Study& study, const json& c, size_t grid_size) {
  const json* hashes = c.contains("sha256") ? &c.at("sha256") : nullptr;
  if (hashes && hashes->size() != grid_size + 1)
    throw std::invalid_argument("a condition's sha256 list needs the reference and every λ image");
  std::vector<int>& slots = study.condition_images.emplace_back();
  for (size_t k = 0; k <= grid_size; ++k) {
    runtime::StimulusImage image;
    image.sha256 = hashes ? hashes->at(k).get<std::string>() : (k == 0 ? "reference" : "λ");
    study.images.push_back(image);
    study.stimuli.push_back({{int(study.images.size()) - 1}, 0, ""});
    slots.push_back(int(study.stimuli.size()) - 1);
  }
}

procedures::PlanSettings plan_settings_of(const json& page, uint64_t seed) {
  procedures::PlanSettings s;
  s.seed = seed;
  s.repetitions = page.at("repetitions").get<int>();
  s.side = side_named(page.at("side").get<std::string>());
  s.start =
      page.at("start") == "zero" ? procedures::StartMode::zero : procedures::StartMode::random;
  s.practice_trials = page.at("practice_trials").get<int>();
  s.practice_conditions = page.at("practice_conditions").get<std::vector<int>>();
  return s;
}

}  // namespace

procedures::Side side_named(const std::string& name) {
  if (name == "left") return procedures::Side::left;
  if (name == "right") return procedures::Side::right;
  return procedures::Side::counterbalanced;
}

std::vector<adjust::Trial> page_plan(const json& page, const std::string& subject, int session) {
  return adjust::plan_trials(study_from_page(page).conditions,
                             plan_settings_of(page, page_session_seed(page, subject, session)));
}

runtime::Study study_from_page(const json& page) {
  runtime::Study study;
  study.lambda_min = page.at("lambda_grid").at("min").get<double>();
  study.lambda_step = page.at("lambda_grid").at("step").get<double>();
  for (const json& c : page.at("conditions")) {
    const size_t grid_size = c.at("grid").size();
    study.conditions.push_back({c.at("scene").get<std::string>(), c.at("method").get<std::string>(),
                                c.at("sigma_value").get<double>(), int(grid_size)});
    add_condition_images(study, c, grid_size);
  }
  return study;
}

uint64_t page_session_seed(const json& page, const std::string& subject, int session) {
  return runtime::session_seed(std::stoull(page.at("seed").get<std::string>()), subject, session);
}

}  // namespace countershade::web_engine
