#pragma once
// GUI tests: a private Xvfb server (Mesa llvmpipe renders into it) and the real binary started
// as a child process on it, so tests can wait for it, or kill it.

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace countershade::testing {

class XvfbServer {
 public:
  explicit XvfbServer(const std::string& screen = "1280x1024x24") {
    int fds[2];
    if (::pipe(fds) != 0) throw std::runtime_error("pipe");
    pid_ = ::fork();
    if (pid_ == 0) {
      ::close(fds[0]);
      int null = ::open("/dev/null", O_WRONLY);
      ::dup2(null, 1);
      ::dup2(null, 2);
      const std::string fd = std::to_string(fds[1]);
      ::execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", screen.c_str(),
               "-nolisten", "tcp", "-noreset", nullptr);
      ::_exit(127);
    }
    ::close(fds[1]);
    // Xvfb writes the display number it chose once it accepts connections.
    std::string number;
    pollfd p{fds[0], POLLIN, 0};
    char c;
    while (::poll(&p, 1, 20000) > 0 && ::read(fds[0], &c, 1) == 1 && c != '\n') number += c;
    ::close(fds[0]);
    if (number.empty())
      throw std::runtime_error(
          "Xvfb did not start (is the xvfb package installed? see scripts/setup)");
    display_ = ":" + number;
  }
  ~XvfbServer() {
    if (pid_ > 0) {
      ::kill(pid_, SIGTERM);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  const std::string& display() const { return display_; }

 private:
  pid_t pid_ = -1;
  std::string display_;
};

// A child process with DISPLAY set; its stdout and stderr go to `log`.
class Child {
 public:
  Child(const std::vector<std::string>& argv, const std::string& display, const std::string& log) {
    pid_ = ::fork();
    if (pid_ == 0) {
      ::setenv("DISPLAY", display.c_str(), 1);
      // Under the sanitizer build: Mesa's driver leaks a few bytes and is unloaded at exit, so
      // LeakSanitizer cannot name (or suppress) it. Leaks of countershade's own code are caught
      // by the in-process tests of the procedure, study and recorder.
      const char* lsan = std::getenv("LSAN_OPTIONS");
      ::setenv("LSAN_OPTIONS", (std::string(lsan ? lsan : "") + ":detect_leaks=0").c_str(), 1);
      int out = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
      ::dup2(out, 1);
      ::dup2(out, 2);
      std::vector<char*> args;
      for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
      args.push_back(nullptr);
      ::execv(args[0], args.data());
      ::_exit(127);
    }
  }
  ~Child() {
    if (running()) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  bool running() {
    if (done_) return false;
    int status = 0;
    if (::waitpid(pid_, &status, WNOHANG) == pid_) finish(status);
    return !done_;
  }
  // Waits up to `seconds`; returns the exit status, or -1 if it is still running.
  int wait(double seconds) {
    auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (running() && std::chrono::steady_clock::now() < until)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    return done_ ? exit_code_ : -1;
  }
  void kill_hard() {
    if (!running()) return;
    ::kill(pid_, SIGKILL);
    int status = 0;
    ::waitpid(pid_, &status, 0);
    finish(status);
  }
  bool killed() const { return signalled_; }
  // Sends a signal (SIGTERM, SIGINT) without waiting.
  void send(int signal) {
    if (running()) ::kill(pid_, signal);
  }

 private:
  void finish(int status) {
    done_ = true;
    signalled_ = WIFSIGNALED(status);
    exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  }
  pid_t pid_ = -1;
  bool done_ = false, signalled_ = false;
  int exit_code_ = -1;
};

}  // namespace countershade::testing
