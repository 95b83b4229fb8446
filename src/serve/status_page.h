#pragma once
// The lab's view of a running study (GET /admin, /admin/status.json with the admin token):
// sessions started, completed and abandoned, rows per session, the last activity, and the
// requests refused since the server started, by kind.

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "serve/study_records.h"

namespace countershade::serve {

using RefusalCounts = std::map<std::string, int64_t>;

std::string status_html(const StudyRecords& records, const RefusalCounts& refusals,
                        int64_t answers_expected);
nlohmann::json status_json(const StudyRecords& records, const RefusalCounts& refusals,
                           int64_t answers_expected);

}  // namespace countershade::serve
