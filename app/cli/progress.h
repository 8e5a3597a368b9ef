// Progress on stderr for long commands: a live line on a terminal, a line every 10 % else.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>
#include <unistd.h>

namespace hdrf::cli {

class Progress {
 public:
  Progress(std::string what, int total)
      : what_(std::move(what)), total_(total), tty_(isatty(fileno(stderr))),
        start_(std::chrono::steady_clock::now()) {}
  void Step() {
    ++done_;
    const int pct = total_ ? 100 * done_ / total_ : 100;
    if (tty_) {
      std::fprintf(stderr, "\r%s: %d/%d (%d %%, %.1f frames/s)   ", what_.c_str(), done_, total_,
                   pct, Rate());
    } else if (pct / 10 != last_decile_) {
      last_decile_ = pct / 10;
      std::fprintf(stderr, "%s: %d/%d (%d %%)\n", what_.c_str(), done_, total_, pct);
    }
  }
  void Done() {
    if (tty_) std::fprintf(stderr, "\n");
  }
  double Rate() const {
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    return s > 0 ? done_ / s : 0;
  }

 private:
  std::string what_;
  int total_, done_ = 0, last_decile_ = -1;
  bool tty_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace hdrf::cli
