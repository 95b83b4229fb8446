#include "procedures/condition_selection.h"

namespace countershade::procedures {

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

}  // namespace countershade::procedures
