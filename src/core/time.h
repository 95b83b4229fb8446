#pragma once
// Wall-clock timestamps for manifests, sidecars and logs.

#include <string>

namespace countershade {

// UTC now, ISO 8601: "2026-11-22T03:45:43Z", or with milliseconds "2026-11-22T03:45:43.123Z".
std::string utc_timestamp(bool milliseconds = true);

}  // namespace countershade
