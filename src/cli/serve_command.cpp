// `countershade serve`: hosts an exported study and keeps every answer in a SQLite database
// (docs/online-study.md, "Hosting with countershade serve"); also makes participant links and
// exports the sessions as the apps' CSV files.

#include <sys/stat.h>

#include <cstdio>
#include <fstream>
#include <memory>

#include "cli/commands.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/file_bytes.h"
#include "runtime/study.h"
#include "serve/study_records.h"
#include "serve/study_server.h"
#include "serve/tokens.h"

namespace countershade::cli {
namespace {

namespace fs = std::filesystem;

struct ServeArgs {
  std::string study, data, export_folder, links_csv, admin_token_file, url, prefix = "P";
  int links = 0;
  double abandoned_after_min = 60;
  serve::ServeOptions options;
};

// The links as a CSV the lab hands out: subject, session and URL. The tokens exist nowhere else,
// so an existing file is never overwritten; the file is readable by its owner only.
void write_links(const ServeArgs& a) {
  if (a.links_csv.empty()) throw_input_error("--links", "needs --links-csv FILE to write them to");
  if (fs::exists(a.links_csv))
    throw_input_error(a.links_csv, "exists; links are never overwritten");
  runtime::check_subject_id(a.prefix + "001");
  const serve::StudyFolder folder = serve::open_study_folder(a.study);
  // Links can be added while the study runs: the server reads them from the database at claims.
  serve::StudyDatabase database(a.data, folder, serve::StudyDatabase::Holder::beside_server);
  const std::string base =
      a.url.empty() ? "http://" + a.options.bind + ":" + std::to_string(a.options.port) + "/"
                    : a.url;
  std::string csv = "subject,session,url\n";
  for (const serve::NewLink& link : database.add_links(a.links, a.prefix))
    csv += link.subject + "," + std::to_string(link.session) + "," + base + "?link=" + link.token +
           "\n";
  const mode_t old_mask = ::umask(077);
  write_text_atomically(a.links_csv, csv);
  ::umask(old_mask);
  std::printf("wrote %d links to %s\n", a.links, a.links_csv.c_str());
}

// The admin token: read from --admin-token-file when it exists, else made (and written there).
std::string admin_token(const ServeArgs& a) {
  if (!a.admin_token_file.empty() && fs::exists(a.admin_token_file)) {
    std::string token = read_file_bytes(a.admin_token_file);
    while (!token.empty() && (token.back() == '\n' || token.back() == '\r')) token.pop_back();
    if (!serve::is_token(token))
      throw_input_error(a.admin_token_file, "does not hold a token (32 lowercase hex digits)");
    return token;
  }
  const std::string token = serve::random_token();
  if (!a.admin_token_file.empty()) {
    const mode_t old_mask = ::umask(077);
    write_text_atomically(a.admin_token_file, token + "\n");
    ::umask(old_mask);
  }
  return token;
}

void run_server(ServeArgs& a) {
  serve::block_stop_signals();
  const serve::StudyFolder folder = serve::open_study_folder(a.study);
  serve::StudyDatabase database(a.data, folder);
  if (!a.options.open && !database.has_links())
    throw_input_error(a.data, "has no participant links: make some with --links N, or pass --open");
  a.options.admin_token = admin_token(a);
  a.options.abandoned_after_s = a.abandoned_after_min * 60;
  serve::serve_study(folder, database, a.options, [&](const std::string& url) {
    std::printf(
        "%s\nadmin: %sadmin?token=%s\n", url.c_str(), url.c_str(),
        a.admin_token_file.empty() ? a.options.admin_token.c_str() : "(in --admin-token-file)");
    std::fflush(stdout);
  });
}

void run(ServeArgs& a) {
  if (!a.export_folder.empty()) {
    const size_t files = serve::export_sessions(a.data, a.export_folder);
    std::printf("wrote %zu session files to %s\n", files, a.export_folder.c_str());
    return;
  }
  if (a.study.empty()) throw_input_error("STUDY_DIR", "required (a folder written by export-web)");
  if (a.links > 0) return write_links(a);
  run_server(a);
}

}  // namespace

void add_serve_command(CLI::App& app) {
  auto args = std::make_shared<ServeArgs>();
  serve::ServeOptions& o = args->options;
  CLI::App* cmd = app.add_subcommand("serve", kServeDescription);
  cmd->add_option("study", args->study, "The folder export-web wrote")
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--data", args->data, "The study's SQLite database (created when missing)")
      ->required();
  cmd->add_option("--bind", o.bind, "Address to listen on (a reverse proxy adds TLS)")
      ->capture_default_str();
  cmd->add_option("--port", o.port, "Port to listen on; 0 picks a free one")
      ->capture_default_str()
      ->check(CLI::Range(0, 65535));
  cmd->add_flag("--open", o.open,
                "Let participants start a session without a link (the page asks for an id)");
  cmd->add_option("--links", args->links,
                  "Make N one-time participant links, write them to --links-csv and exit")
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--links-csv", args->links_csv,
                  "Where --links writes subject,session,url (never overwritten)");
  cmd->add_option("--url", args->url,
                  "The study's public URL, for the links (default: the listening address)");
  cmd->add_option("--subject-prefix", args->prefix,
                  "Links' subject ids are PREFIX001, PREFIX002, …")
      ->capture_default_str();
  cmd->add_option("--admin-token-file", args->admin_token_file,
                  "Read the admin token from FILE, or write a new one there");
  cmd->add_option("--export", args->export_folder,
                  "Write each session's CSV into FOLDER and exit (works while the study runs)");
  cmd->add_option("--body-limit", o.body_limit, "Largest request body in bytes")
      ->capture_default_str()
      ->check(CLI::Range(1024, 1 << 24));
  cmd->add_option("--rate", o.rate, "Requests per second per participant, on average")
      ->capture_default_str()
      ->check(kPositive);
  cmd->add_option("--burst", o.burst, "Requests per participant in a burst")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 1e6));
  cmd->add_option("--threads", o.threads, "Connections served at once")
      ->capture_default_str()
      ->check(CLI::Range(2, 4096));
  cmd->add_option("--abandoned-after", args->abandoned_after_min,
                  "Minutes without an answer after which an unfinished session counts as abandoned")
      ->capture_default_str()
      ->check(kPositive);
  cmd->callback([args] { run(*args); });
}

}  // namespace countershade::cli
