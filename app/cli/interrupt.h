// Ctrl-C as a request to stop, for commands that keep what they have done (record,
// capture-sweep): while a StopOnInterrupt lives, SIGINT sets its flag instead of ending the
// process; the previous handler comes back when it goes.
#pragma once

#include <atomic>
#include <csignal>

namespace hdrf::cli {

namespace detail {
inline std::atomic<bool> g_interrupted{false};
extern "C" inline void OnInterrupt(int) { g_interrupted = true; }
}  // namespace detail

class StopOnInterrupt {
 public:
  StopOnInterrupt() : previous_((detail::g_interrupted = false, std::signal(SIGINT, detail::OnInterrupt))) {}
  ~StopOnInterrupt() { std::signal(SIGINT, previous_); }
  StopOnInterrupt(const StopOnInterrupt&) = delete;
  StopOnInterrupt& operator=(const StopOnInterrupt&) = delete;
  const std::atomic<bool>& flag() const { return detail::g_interrupted; }
  bool raised() const { return detail::g_interrupted.load(); }

 private:
  void (*previous_)(int);
};

}  // namespace hdrf::cli
