#include "serve/study_server.h"

#include <httplib.h>
#include <signal.h>
#include <sys/socket.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <map>
#include <mutex>
#include <thread>

#include "core/error.h"
#include "core/file_bytes.h"
#include "core/one_line.h"
#include "formats/responses.h"
#include "runtime/study.h"
#include "serve/posted_row.h"
#include "serve/rate_limit.h"
#include "serve/refusal.h"
#include "serve/session_plan.h"
#include "serve/status_page.h"
#include "serve/tokens.h"

namespace countershade::serve {
namespace {

using httplib::Request;
using httplib::Response;
using nlohmann::json;

// The page's scripts, images and WebAssembly come from this origin only, and it sends rows nowhere
// else. No script may build code at run time: the engine's WebAssembly is compiled in the page
// ('wasm-unsafe-eval'), and its bindings are linked without `new Function` (DYNAMIC_EXECUTION=0).
// jsPsych sets inline styles, and its style sheet carries its fonts as data: URLs.
constexpr const char* kContentSecurityPolicy =
    "default-src 'self'; script-src 'self' 'wasm-unsafe-eval'; "
    "style-src 'self' 'unsafe-inline'; font-src 'self' data:; img-src 'self' blob: data:; "
    "connect-src 'self'; "
    "frame-ancestors 'none'; base-uri 'none'; form-action 'self'; object-src 'none'";

// The header a refusal carries from the handler to the error handler, which logs and counts it.
constexpr const char* kRefusalHeader = "X-Countershade-Refusal";

// A subject id as the apps take one (it becomes a file name).
bool is_subject_id(const std::string& subject) {
  try {
    runtime::check_subject_id(subject);
    return true;
  } catch (const InputError&) {
    return false;
  }
}

std::string bearer_token(const Request& req) {
  const std::string value = req.get_header_value("Authorization");
  const std::string prefix = "Bearer ";
  return value.rfind(prefix, 0) == 0 ? value.substr(prefix.size()) : "";
}

class StudyServer {
 public:
  StudyServer(const StudyFolder& folder, StudyDatabase& database, const ServeOptions& options)
      : folder_(folder),
        database_(database),
        options_(options),
        limit_(options.rate, options.burst),
        admin_hash_(token_hash(options.admin_token)),
        answers_expected_(SessionPlan(folder, "plan", 1).answers_expected()) {}

  void route(httplib::Server& server);

 private:
  void refuse(Response& res, const Refusal& refusal) const;
  void handle_errors(const Request& req, Response& res);
  void send_file(const Request& req, Response& res) const;
  void claim(const Request& req, Response& res);
  void store(const Request& req, Response& res);
  SessionRecord session_of(const Request& req);
  std::shared_ptr<SessionPlan> plan_of(const SessionRecord& session);
  // Lets go of a session's plan: it is made again from the stored rows if the session posts again.
  void forget_plan(int64_t session_id);
  size_t plans_held();
  bool is_admin(const Request& req) const;
  void status(const Request& req, Response& res, bool html);
  // Runs a handler, answering its Refusal (4xx, nothing written) instead of what it would have.
  template <typename Handler>
  auto guarded(Handler handler) {
    return [this, handler](const Request& req, Response& res) {
      try {
        handler(req, res);
      } catch (const Refusal& refusal) {
        refuse(res, refusal);
      } catch (const std::exception& e) {  // the server's own failure, never the client's
        refuse(res, Refusal(500, "server failure", e.what()));
      }
    };
  }

  const StudyFolder& folder_;
  StudyDatabase& database_;
  const ServeOptions& options_;
  RateLimit limit_;
  // The plans of the sessions under way, by session id, with when each was last used. A plan
  // holds the session's procedures (QUEST+ posteriors), so completed sessions and those idle
  // longer than --abandoned-after are let go.
  struct HeldPlan {
    std::shared_ptr<SessionPlan> plan;
    std::chrono::steady_clock::time_point used;
  };
  std::mutex plans_mutex_;
  std::map<int64_t, HeldPlan> plans_;
  std::string admin_hash_;
  int answers_expected_;
  mutable std::mutex refusals_mutex_;
  std::map<std::string, int64_t> refusals_;  // by kind, since the server started
};

void StudyServer::refuse(Response& res, const Refusal& refusal) const {
  res.status = refusal.status;
  res.set_header(kRefusalHeader, refusal.kind);
  res.set_content(json{{"error", refusal.kind}, {"detail", refusal.what()}}.dump(),
                  "application/json");
  res.set_header("X-Countershade-Detail", one_line(refusal.what()));
}

// Every response of 400 or more passes here, the server's own (a body over the limit) and the
// handlers' refusals: one line in the log and one count on the status page.
void StudyServer::handle_errors(const Request& req, Response& res) {
  std::string kind = res.get_header_value(kRefusalHeader);
  std::string detail = res.get_header_value("X-Countershade-Detail");
  if (kind.empty())
    kind = res.status == 413 ? "oversized body" : "status " + std::to_string(res.status);
  res.headers.erase("X-Countershade-Detail");
  {
    std::lock_guard lock(refusals_mutex_);
    ++refusals_[kind];
  }
  std::fprintf(stderr, "serve: refused %d (%s) %s %s from %s%s%s\n", res.status, kind.c_str(),
               req.method.c_str(), one_line(req.path).substr(0, 200).c_str(),
               req.remote_addr.c_str(), detail.empty() ? "" : ": ", detail.c_str());
  if (res.body.empty()) res.set_content(json{{"error", kind}}.dump(), "application/json");
}

void StudyServer::send_file(const Request& req, Response& res) const {
  const auto file = study_file(folder_, req.path);
  if (!file) throw Refusal(404, "not found", "no such file in the study");
  res.set_content(read_file_bytes(*file), content_type(*file));
  res.set_header("Cache-Control", "no-cache");
}

void StudyServer::claim(const Request& req, Response& res) {
  if (!limit_.allow("address " + req.remote_addr))
    throw Refusal(429, "too many requests", "claims from this address come too fast");
  const std::string token = bearer_token(req);
  if (!is_token(token)) throw Refusal(401, "no token", "claim: Authorization: Bearer TOKEN");
  const json body = json::parse(req.body, nullptr, false);
  if (!body.is_object()) throw Refusal(400, "malformed claim", "claim: not a JSON object");
  SessionRecord session;
  if (body.contains("link") && body["link"].is_string() && is_token(body["link"])) {
    session = database_.claim_link(token_hash(body["link"]), token_hash(token));
  } else {
    if (!options_.open)
      throw Refusal(403, "no link", "claim: this study takes participants by link");
    // A field of another type is a malformed claim, not the server's failure.
    const json subject_field = body.value("subject", json()),
               number_field = body.value("session", json(1));
    const std::string subject = subject_field.is_string() ? subject_field.get<std::string>() : "";
    const int64_t number = number_field.is_number_integer() ? number_field.get<int64_t>() : 0;
    if (!is_subject_id(subject) || number < 1 || number > 99)
      throw Refusal(400, "malformed claim", "claim: a subject id and a session from 1 to 99");
    session = database_.open_session(subject, int(number), token_hash(token));
  }
  res.set_content(json{{"subject", session.subject}, {"session", session.session}}.dump(),
                  "application/json");
}

SessionRecord StudyServer::session_of(const Request& req) {
  const std::string token = bearer_token(req);
  const auto session = is_token(token) ? database_.session_of(token_hash(token)) : std::nullopt;
  if (!session) throw Refusal(403, "forged token", "row: the token holds no session");
  if (!limit_.allow(token)) throw Refusal(429, "too many requests", "rows come too fast");
  return *session;
}

// The session's plan, made when a server first sees the session, and brought up to the rows
// stored before (by an earlier run of the server).
std::shared_ptr<SessionPlan> StudyServer::plan_of(const SessionRecord& session) {
  std::lock_guard lock(plans_mutex_);
  const auto now = std::chrono::steady_clock::now();
  const auto idle = std::chrono::duration<double>(options_.abandoned_after_s);
  std::erase_if(plans_, [&](const auto& held) {
    return held.first != session.id && now - held.second.used > idle;
  });
  HeldPlan& held = plans_[session.id];
  held.used = now;
  if (held.plan) return held.plan;
  auto plan = std::make_shared<SessionPlan>(folder_, session.subject, session.session);
  bool completed = false;
  for (const std::string& line : database_.lines_of(session))
    completed = plan->record(parse_csv(line, "stored row").rows.at(0));
  if (completed) {  // (a repeat of a row it has): answered, and not kept
    database_.mark_completed(session);
    plans_.erase(session.id);
  } else {
    held.plan = plan;
  }
  return plan;
}

void StudyServer::forget_plan(int64_t session_id) {
  std::lock_guard lock(plans_mutex_);
  plans_.erase(session_id);
}

size_t StudyServer::plans_held() {
  std::lock_guard lock(plans_mutex_);
  return plans_.size();
}

// A new row (the next index) is checked against the plan; a repeat or a gap is left to the
// database, which answers a repeat 200 and anything else 409. The session's mutex keeps the
// check, the write and the plan's step together.
void StudyServer::store(const Request& req, Response& res) {
  const std::string type = req.get_header_value("Content-Type");
  if (type != "text/csv" && type.rfind("text/csv;", 0) != 0)
    throw Refusal(415, "wrong content type", "row: Content-Type is not text/csv");
  const SessionRecord session = session_of(req);
  const long index = row_index_of_key(req.get_header_value("Idempotency-Key"),
                                      page_store_key(folder_, session.subject, session.session));
  const std::vector<std::string> fields = parse_posted_row(req.body, folder_.columns);
  const std::shared_ptr<SessionPlan> plan = plan_of(session);
  std::lock_guard lock(plan->mutex());
  const bool next = index == plan->rows_stored;
  const std::string answer = next ? plan->check(fields) : "";
  const RowStored stored = database_.store_row(session, index, csv_line(fields), answer);
  if (stored == RowStored::added && plan->record(fields)) {
    database_.mark_completed(session);
    forget_plan(session.id);
  }
  res.status = stored == RowStored::added ? 201 : 200;
  res.set_content(json{{"row", index}, {"stored", stored == RowStored::added}}.dump(),
                  "application/json");
}

bool StudyServer::is_admin(const Request& req) const {
  const std::string token =
      req.has_param("token") ? req.get_param_value("token") : bearer_token(req);
  return is_token(token) && token_hash(token) == admin_hash_;
}

void StudyServer::status(const Request& req, Response& res, bool html) {
  if (!is_admin(req)) throw Refusal(403, "not the admin token", "status: needs the admin token");
  const StudyRecords records =
      read_records(database_.file(), answers_expected_, options_.abandoned_after_s);
  std::map<std::string, int64_t> refusals;
  {
    std::lock_guard lock(refusals_mutex_);
    refusals = refusals_;
  }
  if (html)
    res.set_content(status_html(records, refusals, answers_expected_), "text/html; charset=utf-8");
  else {
    nlohmann::json body = status_json(records, refusals, answers_expected_);
    body["plans_held"] = plans_held();
    res.set_content(body.dump(1), "application/json");
  }
  res.set_header("Cache-Control", "no-store");
}

void StudyServer::route(httplib::Server& server) {
  server.Get("/countershade-serve.json", [this](const Request&, Response& res) {
    res.set_content(
        json{{"claim", "api/claim"}, {"rows", "api/rows"}, {"open", options_.open}}.dump(),
        "application/json");
    res.set_header("Cache-Control", "no-store");
  });
  server.Post("/api/claim", guarded([this](const Request& q, Response& r) { claim(q, r); }));
  server.Post("/api/rows", guarded([this](const Request& q, Response& r) { store(q, r); }));
  server.Get("/admin", guarded([this](const Request& q, Response& r) { status(q, r, true); }));
  server.Get("/admin/status.json",
             guarded([this](const Request& q, Response& r) { status(q, r, false); }));
  server.Get(".*", guarded([this](const Request& q, Response& r) { send_file(q, r); }));
  server.set_error_handler([this](const Request& q, Response& r) { handle_errors(q, r); });
}

sigset_t stop_signals() {
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  return signals;
}

// SIGINT and SIGTERM stop the server: requests under way are answered, and the writer commits
// what it holds before the database closes.
std::thread stop_on_signals(httplib::Server& server) {
  return std::thread([&server] {
    const sigset_t signals = stop_signals();
    int signal = 0;
    sigwait(&signals, &signal);
    std::fprintf(stderr, "serve: stopping (signal %d)\n", signal);
    server.stop();
  });
}

// Binds the socket. Debian's cpp-httplib listens with a backlog of 5 connections, so that when a
// few hundred participants connect at once, the kernel drops most of their first attempts and
// each waits a second to try again; listening again on the bound socket raises the backlog.
int bind_listening_socket(httplib::Server& server, const ServeOptions& options) {
  int socket = -1;
  // SO_REUSEADDR alone: a restarted server binds at once beside its predecessor's closing
  // connections. cpp-httplib's default adds SO_REUSEPORT, which would let a second server share
  // the port and take half the requests.
  server.set_socket_options([&socket](int s) {
    const int yes = 1;
    ::setsockopt(s, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    socket = s;
  });
  const int port = options.port == 0 ? server.bind_to_any_port(options.bind)
                   : server.bind_to_port(options.bind, options.port) ? options.port
                                                                     : -1;
  if (port < 0)
    throw_input_error("--port",
                      "cannot listen on " + options.bind + ":" + std::to_string(options.port));
  ::listen(socket, SOMAXCONN);
  return port;
}

}  // namespace

void block_stop_signals() {
  const sigset_t signals = stop_signals();
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
}

void serve_study(const StudyFolder& folder, StudyDatabase& database, const ServeOptions& options,
                 const std::function<void(const std::string& url)>& on_listening) {
  httplib::Server server;
  StudyServer study(folder, database, options);
  study.route(server);
  server.set_payload_max_length(options.body_limit);
  server.set_keep_alive_max_count(1000);
  server.set_default_headers({{"Content-Security-Policy", kContentSecurityPolicy},
                              {"X-Content-Type-Options", "nosniff"},
                              {"Referrer-Policy", "no-referrer"},
                              {"Cross-Origin-Resource-Policy", "same-origin"}});
  const int threads = options.threads;
  server.new_task_queue = [threads] { return new httplib::ThreadPool(size_t(threads)); };
  const int port = bind_listening_socket(server, options);
  std::thread watcher = stop_on_signals(server);
  const bool v6 = options.bind.find(':') != std::string::npos;
  on_listening("http://" + (v6 ? "[" + options.bind + "]" : options.bind) + ":" +
               std::to_string(port) + "/");
  server.listen_after_bind();
  watcher.join();
}

}  // namespace countershade::serve
