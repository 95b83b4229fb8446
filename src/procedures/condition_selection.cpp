#include "procedures/condition_selection.h"

#include <cmath>

namespace countershade::procedures {

bool ConditionSelection::names(const std::string& s, const std::string& m, double sg) const {
  return scene == s && method == m && std::abs(sigma - sg) < 1e-12;
}

std::vector<ConditionSelection> read_condition_selections(const JsonObject& block,
                                                          const std::string& key) {
  std::vector<ConditionSelection> out;
  if (!block.has(key)) return out;
  for (const auto& s : block.objects(key)) {
    out.push_back({s.string("scene"), s.string("method"), s.number("sigma")});
    s.finish();
  }
  return out;
}

std::vector<ConditionSelection> read_condition_selections(const ParameterBag& bag,
                                                          const std::string& key) {
  const auto list = bag.structured(key);
  if (!list) return {};
  // JsonObject reads a list of objects from the object that holds it: give it one.
  const nlohmann::json holder = {{key, list->value}};
  const std::string& path = list->path;
  const std::string parent =
      path.size() > key.size() ? path.substr(0, path.size() - key.size() - 1) : "";
  return read_condition_selections(JsonObject(holder, list->file, parent), key);
}

}  // namespace countershade::procedures
