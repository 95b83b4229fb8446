#include "serve/status_page.h"

#include "core/xml.h"

namespace countershade::serve {
namespace {

// The sessions per state, in the order a session goes through them.
std::vector<std::pair<std::string, int64_t>> sessions_by_state(const StudyRecords& records) {
  std::vector<std::pair<std::string, int64_t>> counts = {
      {"started", 0}, {"completed", 0}, {"abandoned", 0}};
  for (const SessionState& s : records.sessions)
    for (auto& [state, count] : counts) count += s.state == state;
  return counts;
}

std::string cell(const std::string& text) { return "<td>" + xml_escape(text) + "</td>"; }

std::string sessions_table(const StudyRecords& records, int64_t expected) {
  std::string html =
      "<table><tr><th>subject</th><th>session</th><th>state</th><th>rows</th><th>answers</th>"
      "<th>started</th><th>last activity</th></tr>\n";
  for (const SessionState& s : records.sessions)
    html += "<tr>" + cell(s.subject) + cell(std::to_string(s.session)) + cell(s.state) +
            cell(std::to_string(s.rows)) +
            cell(std::to_string(s.answers) + (expected ? " of " + std::to_string(expected) : "")) +
            cell(s.started) + cell(s.last_activity) + "</tr>\n";
  return html + "</table>\n";
}

}  // namespace

std::string status_html(const StudyRecords& records, const RefusalCounts& refusals,
                        int64_t expected) {
  std::string html =
      "<!doctype html><html lang=\"en\"><head><meta charset=\"utf-8\">"
      "<meta http-equiv=\"refresh\" content=\"30\"><title>" +
      xml_escape(records.title) +
      ": status</title><style>body{font-family:sans-serif;margin:2em}td,th{padding:2px "
      "10px;white-space:nowrap;"
      "text-align:left}</style></head><body>\n<h1>" +
      xml_escape(records.title) + "</h1>\n<p>Set " + xml_escape(records.set_sha256) +
      ", exported by countershade " + xml_escape(records.app_version) + ".</p>\n<p>";
  for (const auto& [state, count] : sessions_by_state(records))
    html += xml_escape(state) + ": <b>" + std::to_string(count) + "</b> &nbsp; ";
  if (records.links)
    html += "links claimed: <b>" + std::to_string(records.links_claimed) + " of " +
            std::to_string(records.links) + "</b>";
  html += "</p>\n<h2>Sessions</h2>\n" + sessions_table(records, expected);
  html += "<h2>Refused requests since the server started</h2>\n";
  if (refusals.empty()) html += "<p>None.</p>\n";
  for (const auto& [kind, count] : refusals)
    html += "<p>" + xml_escape(kind) + ": " + std::to_string(count) + "</p>\n";
  return html + "</body></html>\n";
}

nlohmann::json status_json(const StudyRecords& records, const RefusalCounts& refusals,
                           int64_t expected) {
  const auto by_state = sessions_by_state(records);
  const std::map<std::string, int64_t> states(by_state.begin(), by_state.end());
  nlohmann::json sessions = nlohmann::json::array();
  for (const SessionState& s : records.sessions)
    sessions.push_back({{"subject", s.subject},
                        {"session", s.session},
                        {"state", s.state},
                        {"rows", s.rows},
                        {"answers", s.answers},
                        {"started", s.started},
                        {"last_activity", s.last_activity}});
  return {{"title", records.title},
          {"set_sha256", records.set_sha256},
          {"app_version", records.app_version},
          {"answers_per_session", expected},
          {"links", records.links},
          {"links_claimed", records.links_claimed},
          {"states", nlohmann::json(states)},
          {"sessions", sessions},
          {"refused", refusals}};
}

}  // namespace countershade::serve
