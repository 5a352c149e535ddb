#pragma once
// rocking_study's progress on stderr: a redrawn bar on a terminal, a line every ~10 % or 30 s otherwise.

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>

namespace rocking_monitor::tools::study {

inline std::string duration_text(double s) {
  if (!std::isfinite(s) || s < 0) return "--";
  char buf[32];
  const long t = std::lround(s);
  if (t >= 3600)
    std::snprintf(buf, sizeof buf, "%ldh%02ldm", t / 3600, (t / 60) % 60);
  else if (t >= 60)
    std::snprintf(buf, sizeof buf, "%ldm%02lds", t / 60, t % 60);
  else
    std::snprintf(buf, sizeof buf, "%lds", t);
  return buf;
}

// Progress on stderr: a redrawn bar on a terminal, a line every ~10 % or 30 s otherwise.
class ProgressBar {
 public:
  explicit ProgressBar(bool enabled) : enabled_(enabled), tty_(::isatty(2) != 0) {
    start_ = last_line_ = std::chrono::steady_clock::now();
  }
  void operator()(std::size_t done, std::size_t total) {
    if (!enabled_ || total == 0) return;
    const auto now = std::chrono::steady_clock::now();
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double rate = elapsed > 0 ? done / elapsed : 0.0;
    const double left = rate > 0 ? (total - done) / rate : NAN;
    const double frac = static_cast<double>(done) / total;
    char line[200];
    if (tty_) {
      const int width = 30, fill = static_cast<int>(frac * width);
      std::string bar(static_cast<std::size_t>(fill), '=');
      if (fill < width) bar += '>' + std::string(static_cast<std::size_t>(width - fill - 1), ' ');
      std::snprintf(line, sizeof line, "\r[%s] %5.1f%%  %zu/%zu cases  %.0f cases/s  left %s   ",
                    bar.c_str(), 100 * frac, done, total, rate, duration_text(left).c_str());
      std::cerr << line << (done == total ? "\n" : "") << std::flush;
    } else {
      const double since = std::chrono::duration<double>(now - last_line_).count();
      const int decile = static_cast<int>(frac * 10);
      if (done == total || decile > last_decile_ || since > 30) {
        std::snprintf(line, sizeof line, "rocking_study: %5.1f%%  %zu/%zu cases  %.0f cases/s  left %s\n",
                      100 * frac, done, total, rate, duration_text(left).c_str());
        std::cerr << line << std::flush;
        last_decile_ = decile;
        last_line_ = now;
      }
    }
  }

 private:
  bool enabled_, tty_;
  int last_decile_ = 0;
  std::chrono::steady_clock::time_point start_, last_line_;
};

}  // namespace rocking_monitor::tools::study
