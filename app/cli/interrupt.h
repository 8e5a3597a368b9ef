// Ctrl-C (SIGINT) and a request to end (SIGTERM, SIGHUP: a closed terminal, a service
// stopped) as a request to stop, for commands that keep what they have done (scan, export,
// record, capture-sweep): while a StopOnInterrupt lives, these signals set its flag instead of
// ending the process, so that the command stops between two steps with its outputs either
// complete or unchanged; the previous handlers come back when it goes.
#pragma once

#include <atomic>
#include <csignal>

namespace hdrf::cli {

namespace detail {
inline std::atomic<bool> g_interrupted{false};
inline std::atomic<int> g_signal{0};
extern "C" inline void OnInterrupt(int s) {
  g_signal = s;
  g_interrupted = true;
}
}  // namespace detail

class StopOnInterrupt {
 public:
  StopOnInterrupt() {
    detail::g_signal = 0;
    detail::g_interrupted = false;
    for (int i = 0; i < kCount; ++i) previous_[i] = std::signal(kSignals[i], detail::OnInterrupt);
  }
  ~StopOnInterrupt() {
    for (int i = 0; i < kCount; ++i) std::signal(kSignals[i], previous_[i]);
  }
  StopOnInterrupt(const StopOnInterrupt&) = delete;
  StopOnInterrupt& operator=(const StopOnInterrupt&) = delete;
  const std::atomic<bool>& flag() const { return detail::g_interrupted; }
  bool raised() const { return detail::g_interrupted.load(); }
  // The signal that asked to stop (0: none), what to call it, and the exit status a shell
  // gives a process it ended (128 + the signal).
  int signal() const { return detail::g_signal.load(); }
  const char* name() const { return signal() == SIGINT ? "Ctrl-C" : signal() == SIGTERM ? "SIGTERM" : "SIGHUP"; }
  int exit_status() const { return 128 + signal(); }

 private:
  static constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};
  static constexpr int kCount = 3;
  void (*previous_[kCount])(int);
};

}  // namespace hdrf::cli
