// The tools' progress display: its line and when it is drawn.
#include "progress_meter.hpp"

#include <unistd.h>

#include <cmath>

namespace rocking_monitor::tools {

std::string duration_text(double s) {
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

std::string progress_line(std::size_t done, std::size_t total, double elapsed_s, const std::string& unit) {
  const double rate = elapsed_s > 0 ? done / elapsed_s : 0.0;
  const double left = rate > 0 ? (total - done) / rate : NAN;
  const double frac = total > 0 ? static_cast<double>(done) / total : 0.0;
  const int width = 30, fill = static_cast<int>(frac * width);
  std::string bar(static_cast<std::size_t>(fill), '=');
  if (fill < width) bar += '>' + std::string(static_cast<std::size_t>(width - fill - 1), ' ');
  // slow jobs (a shaking-table test, a margin search) count fractions of a unit per second
  const int decimals = rate >= 10 || rate == 0 ? 0 : rate >= 1 ? 1 : 2;
  char line[256];
  std::snprintf(line, sizeof line, "[%s] %5.1f%%  %zu/%zu %s  %.*f %s/s  left %s", bar.c_str(), 100 * frac, done,
                total, unit.c_str(), decimals, rate, unit.c_str(), duration_text(left).c_str());
  return line;
}

ProgressMeter::ProgressMeter(std::string unit, bool quiet)
    : ProgressMeter(std::move(unit), stderr, !quiet && ::isatty(::fileno(stderr)) != 0) {}

ProgressMeter::ProgressMeter(std::string unit, std::FILE* out, bool shown)
    : unit_(std::move(unit)), out_(out), shown_(shown), start_(std::chrono::steady_clock::now()) {}

void ProgressMeter::update(std::size_t done, std::size_t total) {
  if (!shown_ || total == 0) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  if (finished_) return;
  const auto now = std::chrono::steady_clock::now();
  const bool last = done >= total;
  if (drawn_ && !last && now - last_draw_ < std::chrono::milliseconds(100)) return;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  // trailing blanks wipe what a longer previous line left
  std::fprintf(out_, "\r%s   %s", progress_line(done, total, elapsed, unit_).c_str(), last ? "\n" : "");
  std::fflush(out_);
  drawn_ = true;
  last_draw_ = now;
  finished_ = last;
}

}  // namespace rocking_monitor::tools
