#include "analysis/threshold_model.h"

#include <algorithm>

#include "core/error.h"

namespace countershade::analysis {

const char* threshold_model_name(ThresholdModel model) {
  switch (model) {
    case ThresholdModel::log_normal:
      return "lognormal";
    case ThresholdModel::weibull:
      return "weibull";
    case ThresholdModel::logistic:
      return "logistic";
    case ThresholdModel::log_logistic:
      return "log-logistic";
  }
  return "?";
}

ThresholdModel parse_threshold_model(const std::string& name, const std::string& flag,
                                     const std::vector<ThresholdModel>& allowed) {
  std::string list;
  for (ThresholdModel m : allowed)
    list += std::string(list.empty() ? "" : ", ") + threshold_model_name(m);
  const std::string spelled =
      name == "log-normal" ? "lognormal" : name;  // the psychometric fits' older spelling
  for (ThresholdModel m : allowed)
    if (spelled == threshold_model_name(m)) return m;
  throw InputError(flag + ": unknown model '" + name + "' (expected " + list + ")");
}

}  // namespace countershade::analysis
