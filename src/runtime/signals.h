#pragma once
// SIGTERM and SIGINT during a session: while a SignalGuard lives they are only noted, so that the
// run loop saves what it has and ends cleanly (the sidecar records `terminated` or
// `interrupted`); the previous handlers come back on every way out.

#include <optional>

#include "runtime/session_run.h"

namespace countershade::runtime {

class SignalGuard {
 public:
  SignalGuard();
  ~SignalGuard();
  SignalGuard(const SignalGuard&) = delete;
  SignalGuard& operator=(const SignalGuard&) = delete;

  // How a signal received since the guard began ends the run; none while there was none.
  static std::optional<RunEnd> pending();

 private:
  void (*term_)(int);
  void (*interrupt_)(int);
};

}  // namespace countershade::runtime
