// How often the window refreshes its 2-D views while a scan runs. The scan and the window
// share the machine's cores: every millisecond the window spends tone mapping, painting and
// drawing the 3-D view is taken from the scan. The pacer keeps the window's thread under a
// share of the machine (its CPU time over wall time, measured between refreshes, against
// `share` x cores of one core): where a refresh is cheap or cores are many the views follow
// every frame (no faster than kMinIntervalMs), where it is dear they refresh less often, but
// at least once a second.
#pragma once

#include <algorithm>
#include <cstdint>

namespace hdrf::gui {

class DisplayPacer {
 public:
  static constexpr double kMinIntervalMs = 40, kMaxIntervalMs = 1000;
  // `share`: the window's part of the machine (0.05: a twentieth); `cores`: the machine's.
  DisplayPacer(double share, int cores) : budget_(share * std::max(1, cores)) {}
  // May the views refresh now (wall time, milliseconds)?
  bool Due(std::int64_t now_ms) const { return now_ms >= next_ms_; }
  // A refresh starts now; `thread_cpu_ms`: the window thread's CPU time so far. Its share
  // since the last refresh sets the next interval: the one that would have kept it at the
  // budget, half way from the last (no oscillation on one dear frame).
  void Refreshed(std::int64_t now_ms, double thread_cpu_ms) {
    if (last_wall_ms_ >= 0 && now_ms > last_wall_ms_) {
      const double share = (thread_cpu_ms - last_cpu_ms_) / double(now_ms - last_wall_ms_);
      const double want = std::clamp(interval_ms_ * share / budget_, kMinIntervalMs, kMaxIntervalMs);
      interval_ms_ = 0.5 * (interval_ms_ + want);
    }
    last_wall_ms_ = now_ms;
    last_cpu_ms_ = thread_cpu_ms;
    next_ms_ = now_ms + std::int64_t(interval_ms_);
  }
  // The scan stopped or started: the next refresh at once, measured afresh.
  void Restart() {
    next_ms_ = 0;
    last_wall_ms_ = -1;
  }
  double interval_ms() const { return interval_ms_; }
  double budget() const { return budget_; }  // of one core

 private:
  double budget_;
  double interval_ms_ = kMinIntervalMs;
  std::int64_t next_ms_ = 0, last_wall_ms_ = -1;
  double last_cpu_ms_ = 0;
};

}  // namespace hdrf::gui
