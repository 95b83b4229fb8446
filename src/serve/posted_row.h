#pragma once
// A row as the page POSTs it (web/store.js): a CSV of the study's header line and one row, under
// an Idempotency-Key that names the session and the row's place in it.

#include <string>
#include <string_view>
#include <vector>

namespace countershade::serve {

// The largest row index a key may name: no session has a million answers.
inline constexpr long kMostRowsPerSession = 1000000;

// The row's fields, one per column. Throws Refusal (400) for a body that is not RFC 4180 text of
// exactly `columns` and one row of as many fields.
std::vector<std::string> parse_posted_row(std::string_view body,
                                          const std::vector<std::string>& columns);

// The row index that an Idempotency-Key gives for the session whose page store key is
// `store_key` (page_store_key's): the key is "STORE_KEY:INDEX", the store key URI-encoded or not,
// INDEX decimal without leading zeros. Throws Refusal: 400 for a key
// of no session's form, 403 for another session's key.
long row_index_of_key(const std::string& key, const std::string& store_key);

}  // namespace countershade::serve
