#pragma once
// `countershade serve`: hosts one exported study over HTTP and keeps every answer in its database
// (docs/online-study.md, "Hosting with countershade serve"). The page finds the server through
// countershade-serve.json, claims its session with a token of its own, and POSTs each row with
// that token; the server checks the row against the session's plan and acknowledges it once it
// is durable.

#include <filesystem>
#include <functional>
#include <string>

#include "serve/study_database.h"
#include "serve/study_folder.h"

namespace countershade::serve {

struct ServeOptions {
  std::string bind = "127.0.0.1";
  int port = 8080;    // 0: any free port
  bool open = false;  // participants may start a session without a link
  size_t body_limit = 16 * 1024;
  double rate = 20, burst = 40;  // requests per second per token or address
  int threads = 256;             // connections served at once (a page keeps one open)
  double abandoned_after_s = 3600;
  std::string admin_token;
};

// Blocks SIGINT and SIGTERM in the calling thread and the threads it starts from now on, so that
// serve_study's watcher receives them; call it before any thread starts (the database's writer).
void block_stop_signals();

// Serves until SIGINT or SIGTERM (block_stop_signals first). `on_listening` gets the URL once the
// socket is bound. Throws InputError when the address cannot be bound.
void serve_study(const StudyFolder& folder, StudyDatabase& database, const ServeOptions& options,
                 const std::function<void(const std::string& url)>& on_listening);

}  // namespace countershade::serve
