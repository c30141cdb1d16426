#pragma once
// A progress bar with an estimate of the time left, on stderr. On a terminal it redraws one line
// (carriage return); in a log (ctest, a pipe) it prints a line at every tenth of the work instead,
// so that logs stay readable.

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

namespace lgh::bench {

class ProgressBar {
 public:
  // total: units of work (pixels, points, ...); enabled = false prints nothing.
  ProgressBar(std::string label, double total, bool enabled = true)
      : label_(std::move(label)),
        total_(std::max(total, 1e-300)),
        enabled_(enabled),
        tty_(isatty(STDERR_FILENO) != 0),
        start_(std::chrono::steady_clock::now()) {
    if (enabled_ && !tty_) std::fprintf(stderr, "  %s: started\n", label_.c_str());
  }
  ~ProgressBar() { finish(); }
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  double elapsedSeconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

  // Reports `done` units finished (not thread-safe: call it from one thread).
  void update(double done) {
    if (!enabled_ || finished_) return;
    const double fraction = std::clamp(done / total_, 0.0, 1.0);
    const double elapsed = elapsedSeconds();
    if (tty_) {
      if (elapsed - lastDraw_ < 0.2 && fraction < 1.0) return;
      lastDraw_ = elapsed;
      constexpr int kWidth = 30;
      const int filled = int(fraction * kWidth);
      std::string bar(size_t(filled), '#');
      bar.resize(kWidth, '.');
      std::fprintf(stderr, "\r  [%s] %5.1f%%  %s elapsed, %s  %s\x1b[K", bar.c_str(), 100.0 * fraction,
                   formatSeconds(elapsed).c_str(), remaining(fraction, elapsed).c_str(), label_.c_str());
      std::fflush(stderr);
    } else {
      const int tenth = int(fraction * 10.0);
      if (tenth <= lastTenth_ || tenth == 10) return;
      lastTenth_ = tenth;
      std::fprintf(stderr, "  %s: %d%%, %s elapsed, %s\n", label_.c_str(), tenth * 10, formatSeconds(elapsed).c_str(),
                   remaining(fraction, elapsed).c_str());
    }
  }

  void finish() {
    if (!enabled_ || finished_) return;
    finished_ = true;
    const double elapsed = elapsedSeconds();
    if (tty_)
      std::fprintf(stderr, "\r  %s: done in %s\x1b[K\n", label_.c_str(), formatSeconds(elapsed).c_str());
    else
      std::fprintf(stderr, "  %s: done in %s\n", label_.c_str(), formatSeconds(elapsed).c_str());
  }

  static std::string formatSeconds(double s) {
    char buffer[32];
    if (s < 60)
      std::snprintf(buffer, sizeof buffer, "%.1f s", s);
    else if (s < 3600)
      std::snprintf(buffer, sizeof buffer, "%d min %02d s", int(s) / 60, int(s) % 60);
    else
      std::snprintf(buffer, sizeof buffer, "%d h %02d min", int(s) / 3600, int(s) % 3600 / 60);
    return buffer;
  }

 private:
  std::string remaining(double fraction, double elapsed) const {
    if (fraction <= 0.0 || elapsed < 0.5) return "time left unknown";
    return "~" + formatSeconds(elapsed * (1.0 - fraction) / fraction) + " left";
  }

  std::string label_;
  double total_;
  bool enabled_, tty_;
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
  double lastDraw_ = -1.0;
  int lastTenth_ = 0;
};

}  // namespace lgh::bench
