#pragma once
// A condition an experiment block names ({scene, method, sigma}): which conditions a study runs,
// and which its practice trials show. Both studies' blocks read them the same way.

#include <string>
#include <vector>

#include "core/json_reader.h"
#include "core/parameters.h"

namespace countershade::procedures {

struct ConditionSelection {
  std::string scene, method;
  double sigma = 0;
  // Whether it names that condition: the same scene and method (the set's folder label) and σ
  // within 1e-12, as both studies select their conditions.
  bool names(const std::string& scene, const std::string& method, double sigma) const;
};

// The array under `key` (none when the key is absent); each entry's unknown keys are refused.
std::vector<ConditionSelection> read_condition_selections(const JsonObject& block,
                                                          const std::string& key);
// The same, from a procedure's parameter bag.
std::vector<ConditionSelection> read_condition_selections(const ParameterBag& bag,
                                                          const std::string& key);

}  // namespace countershade::procedures
