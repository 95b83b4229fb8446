// How fast `countershade serve` acknowledges rows, each one durable before its answer: N
// participants send full sessions at once over loopback, each row after the last is acknowledged
// (as the page does), optionally paced. Prints rows per second and the acknowledgement latency's
// median, 99th percentile and maximum. docs/performance.md states the figures.
//   build/bin/serve_load [PARTICIPANTS=200] [ROWS_PER_SECOND_EACH=0: no pause] [REPETITIONS=10]

#include <algorithm>
#include <cstdio>
#include <mutex>

#include "../tests/serve/served_study.h"

namespace {

using namespace countershade;
using Clock = std::chrono::steady_clock;

struct Latencies {
  std::mutex mutex;
  std::vector<double> ms;
};

void participant(const serve::StudyFolder& folder, int port, const std::string& subject,
                 const std::string& link, double pace, unsigned seed, Latencies& latencies) {
  std::mt19937 random(seed);
  const std::string token = testing::browser_token(random);
  const std::vector<std::string> lines = testing::planned_lines(folder, subject, random);
  httplib::Client client("127.0.0.1", port);
  const httplib::Headers auth = {{"Authorization", "Bearer " + token}};
  testing::post_until_ok(client, "/api/claim", auth, "{\"link\":\"" + link + "\"}",
                         "application/json");
  std::vector<double> mine;
  const auto start = Clock::now();
  for (size_t i = 0; i < lines.size(); ++i) {
    if (pace > 0)
      std::this_thread::sleep_until(start + std::chrono::duration<double>(double(i) / pace));
    httplib::Headers headers = auth;
    headers.emplace("Idempotency-Key", testing::row_key(folder, subject, long(i)));
    const auto sent = Clock::now();
    if (testing::post_until_ok(client, "/api/rows", headers, csv_line(folder.columns) + lines[i],
                               "text/csv") /
            100 !=
        2)
      std::fprintf(stderr, "serve_load: a row of %s was refused\n", subject.c_str());
    mine.push_back(std::chrono::duration<double, std::milli>(Clock::now() - sent).count());
  }
  std::lock_guard lock(latencies.mutex);
  latencies.ms.insert(latencies.ms.end(), mine.begin(), mine.end());
}

double percentile(std::vector<double> values, double p) {
  std::sort(values.begin(), values.end());
  return values[std::min(values.size() - 1, size_t(p * double(values.size())))];
}

}  // namespace

int main(int argc, char** argv) {
  const int participants = argc > 1 ? std::atoi(argv[1]) : 200;
  const double pace = argc > 2 ? std::atof(argv[2]) : 0;
  const int repetitions = argc > 3 ? std::atoi(argv[3]) : 10;
  testing::TempDir dir;
  const serve::StudyFolder folder = serve::open_study_folder(
      testing::exported_study(dir, "{\"repetitions\": " + std::to_string(repetitions) + "}"));
  const auto db = dir / "study.sqlite";
  const auto links = testing::make_links(folder.root, db, participants);
  // Paced participants keep to the default rate per token (their claims, all from one address,
  // need the burst); unpaced ones would be held to it.
  const std::vector<std::string> limits =
      pace > 0 ? std::vector<std::string>{"--burst", std::to_string(participants)}
               : std::vector<std::string>{"--rate", "1e6", "--burst", "1e6"};
  testing::ServerProcess server(folder.root, db, limits);
  Latencies latencies;
  std::vector<std::thread> threads;
  const auto start = Clock::now();
  for (int p = 0; p < participants; ++p)
    threads.emplace_back(participant, std::cref(folder), server.port(), links[size_t(p)].first,
                         links[size_t(p)].second, pace, unsigned(p + 1), std::ref(latencies));
  for (auto& t : threads) t.join();
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  server.stop();
  std::printf(
      "%d participants, %zu rows in %.2f s: %.0f rows/s; acknowledgement latency median "
      "%.1f ms, p99 %.1f ms, max %.1f ms\n",
      participants, latencies.ms.size(), seconds, double(latencies.ms.size()) / seconds,
      percentile(latencies.ms, 0.5), percentile(latencies.ms, 0.99), percentile(latencies.ms, 1.0));
}
