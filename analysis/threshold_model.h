#pragma once
// The distributions thresholds are fitted with, one list for both procedures: the censored fits of
// adjustment answers (analysis/fit.h) take log-normal, Weibull and logistic; the psychometric fits
// of forced-choice trials (analysis/psychometric_fit.h) take Weibull, log-logistic and
// log-normal. Log-normal, Weibull and log-logistic work on ln λ; logistic on λ itself.

#include <string>
#include <vector>

namespace countershade::analysis {

enum class ThresholdModel { log_normal, weibull, logistic, log_logistic };

// "lognormal" (or "log-normal"), "weibull", "logistic", "log-logistic". A name outside `allowed`,
// or unknown, is an InputError naming `flag` and the allowed names.
ThresholdModel parse_threshold_model(const std::string& name, const std::string& flag,
                                     const std::vector<ThresholdModel>& allowed);
const char* threshold_model_name(ThresholdModel model);

// The models each fit takes.
inline const std::vector<ThresholdModel> kCensoredModels = {
    ThresholdModel::log_normal, ThresholdModel::weibull, ThresholdModel::logistic};
inline const std::vector<ThresholdModel> kPsychometricModels = {
    ThresholdModel::weibull, ThresholdModel::log_logistic, ThresholdModel::log_normal};

}  // namespace countershade::analysis
