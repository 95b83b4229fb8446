#include "serve/posted_row.h"

#include "core/error.h"
#include "formats/responses.h"
#include "serve/refusal.h"

namespace countershade::serve {

std::vector<std::string> parse_posted_row(std::string_view body,
                                          const std::vector<std::string>& columns) {
  CsvTable table;
  try {
    table = parse_csv(std::string(body), "row");
  } catch (const InputError& e) {
    throw Refusal(400, "malformed row", e.what());
  }
  if (table.rows.size() != 2)
    throw Refusal(400, "malformed row",
                  "row: a POST holds the header and one row, not " +
                      std::to_string(table.rows.size()) + " lines");
  if (table.rows[0] != columns)
    throw Refusal(400, "malformed row", "row: the header is not this study's columns");
  if (table.rows[1].size() != columns.size())
    throw Refusal(400, "malformed row",
                  "row: " + std::to_string(table.rows[1].size()) + " fields, the header has " +
                      std::to_string(columns.size()));
  return std::move(table.rows[1]);
}

long row_index_of_key(const std::string& sent, const std::string& store_key) {
  // The page URI-encodes the store key (a header holds ASCII only), and cpp-httplib decodes
  // header values; of the key's characters only ':' is ever encoded, so either form is taken.
  std::string key = sent;
  for (size_t at; (at = key.find("%3A")) != std::string::npos;) key.replace(at, 3, 1, ':');
  const size_t colon = key.rfind(':');
  const std::string digits = colon == std::string::npos ? "" : key.substr(colon + 1);
  const bool decimal = !digits.empty() && digits.size() <= 7 &&
                       digits.find_first_not_of("0123456789") == std::string::npos &&
                       (digits == "0" || digits[0] != '0');
  if (!decimal || std::stol(digits) >= kMostRowsPerSession)
    throw Refusal(400, "bad idempotency key", "Idempotency-Key: not SESSION:INDEX");
  if (key.compare(0, colon, store_key) != 0 || colon != store_key.size())
    throw Refusal(403, "another session's key",
                  "Idempotency-Key: names another session than the token's");
  return std::stol(digits);
}

}  // namespace countershade::serve
