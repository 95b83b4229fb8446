#pragma once
// What the HTML reports share: tables of JSON rows, and the way they show numbers.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace countershade::analysis {

// A value that could not be computed (NaN, e.g. the standard error of a fit that did not
// converge) is written as R's NA in CSV, "—" in HTML and null in JSON; an infinite one (F with no
// error variance) as R's Inf, "∞" and null.
bool not_available(const nlohmann::ordered_json& v);
bool infinite(const nlohmann::ordered_json& v);

// `v` with `decimals` digits after the point.
std::string fixed(double v, int decimals);

// The rows (JSON objects) as an HTML table of the columns `keys`, every cell escaped.
std::string html_table(const nlohmann::ordered_json& rows, const std::vector<std::string>& keys);

}  // namespace countershade::analysis
