#include "analysis/html_table.h"

#include <cmath>
#include <sstream>

#include "core/xml.h"

namespace countershade::analysis {

using json = nlohmann::ordered_json;

bool not_available(const json& v) {
  return v.is_null() || (v.is_number_float() && std::isnan(v.get<double>()));
}
bool infinite(const json& v) { return v.is_number_float() && std::isinf(v.get<double>()); }

std::string fixed(double v, int decimals) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(decimals);
  s << v;
  return s.str();
}
std::string html_table(const json& rows, const std::vector<std::string>& keys) {
  std::ostringstream out;
  out << "<table><tr>";
  for (const auto& k : keys) out << "<th>" << xml_escape(k) << "</th>";
  out << "</tr>\n";
  for (const auto& row : rows) {
    out << "<tr>";
    for (const auto& k : keys) {
      std::string v = !row.contains(k)           ? ""
                      : not_available(row[k])    ? "—"
                      : infinite(row[k])         ? (row[k].get<double>() > 0 ? "∞" : "−∞")
                      : row[k].is_number_float() ? fixed(row[k], 4)
                      : row[k].is_string()       ? row[k].get<std::string>()
                                                 : row[k].dump();
      out << "<td>" << xml_escape(v) << "</td>";
    }
    out << "</tr>\n";
  }
  out << "</table>\n";
  return out.str();
}

}  // namespace countershade::analysis
