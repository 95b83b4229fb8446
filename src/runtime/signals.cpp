#include "runtime/signals.h"

#include <atomic>
#include <csignal>

namespace countershade::runtime {
namespace {

std::atomic<int> g_signal{0};
void on_signal(int signal) { g_signal = signal; }

}  // namespace

SignalGuard::SignalGuard()
    : term_(std::signal(SIGTERM, on_signal)), interrupt_(std::signal(SIGINT, on_signal)) {
  g_signal = 0;
}

SignalGuard::~SignalGuard() {
  std::signal(SIGTERM, term_);
  std::signal(SIGINT, interrupt_);
}

std::optional<RunEnd> SignalGuard::pending() {
  const int signal = g_signal;
  if (!signal) return std::nullopt;
  return signal == SIGTERM ? RunEnd::terminated : RunEnd::interrupted;
}

}  // namespace countershade::runtime
