#pragma once
// Writing an audit: audit.json and audit.csv for scripts, checks.csv, and report.html for people,
// with the checks as a table coloured by outcome, each condition's measures against λ as SVG
// plots, and a thumbnail strip per condition.

#include <filesystem>

#include "audit/audit.h"

namespace countershade {

void write_audit_report(const AuditReport& report, const std::filesystem::path& dir);

}  // namespace countershade
