// Progress bar / per-cell lines with ETA (cli/progress.h).
#include "cli/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

namespace blocklab::cli {

std::string duration_text(double seconds) {
  const long long whole = std::llround(std::max(0.0, seconds));
  char text[32];
  if (whole < 60) std::snprintf(text, sizeof text, "%llds", whole);
  else if (whole < 3600) std::snprintf(text, sizeof text, "%lldm%02llds", whole / 60, whole % 60);
  else std::snprintf(text, sizeof text, "%lldh%02lldm", whole / 3600, whole / 60 % 60);
  return text;
}

ProgressDisplay::ProgressDisplay(bool enabled, std::string unit)
    : enabled_(enabled), unit_(std::move(unit)), terminal_(isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()), last_draw_(start_), compute_start_(start_) {}

void ProgressDisplay::update(std::size_t done, std::size_t total, std::size_t cached, const std::string& current) {
  if (!enabled_ || total == 0) return;
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  if (!computing_ && !current.empty()) {
    computing_ = true;
    compute_start_ = now;
  }
  const std::size_t computed = done - cached;
  std::string eta = "ETA --";
  if (done == total) {
    eta = "done";
  } else if (computed > 0) {
    const double per_cell = std::chrono::duration<double>(now - compute_start_).count() / computed;
    eta = "ETA " + duration_text(per_cell * static_cast<double>(total - done));
  }
  if (terminal_) {
    if (done < total && now - last_draw_ < std::chrono::milliseconds(100)) return;
    constexpr int kBarWidth = 30;
    const int filled = static_cast<int>(kBarWidth * done / total);
    std::fprintf(stderr, "\r[%.*s%*s] %zu/%zu %s (%zu cached) %s, %-9s %-40.40s", filled,
                 "##############################", kBarWidth - filled, "", done, total, unit_.c_str(), cached,
                 duration_text(elapsed).c_str(), eta.c_str(), current.c_str());
    std::fflush(stderr);
    drew_bar_ = true;
  } else if (current.empty()) {
    std::fprintf(stderr, "progress: %zu/%zu %s (%zu cached) in %s\n", done, total, unit_.c_str(), cached,
                 duration_text(elapsed).c_str());
  } else {
    std::fprintf(stderr, "progress: %zu/%zu %s (%zu cached), %s elapsed, %s; next: %s\n", done, total, unit_.c_str(), cached,
                 duration_text(elapsed).c_str(), eta.c_str(), current.c_str());
  }
  last_draw_ = now;
}

void ProgressDisplay::finish() {
  if (enabled_ && terminal_ && drew_bar_) std::fprintf(stderr, "\n");
  drew_bar_ = false;
}

}  // namespace blocklab::cli
