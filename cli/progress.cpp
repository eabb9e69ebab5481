#include "cli/progress.h"

#include <unistd.h>

#include <cstdio>
#include <utility>

namespace blocklab::cli {

ProgressDisplay::ProgressDisplay(bool enabled, std::string unit)
    : enabled_(enabled), unit_(std::move(unit)), terminal_(isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()), last_draw_(start_) {}

void ProgressDisplay::update(std::size_t done, std::size_t total, std::size_t cached, const std::string& current) {
  if (!enabled_ || total == 0) return;
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  char eta[32] = "ETA ?";
  if (done > 0) std::snprintf(eta, sizeof eta, "ETA %.0fs", elapsed / static_cast<double>(done) * (total - done));
  if (terminal_) {
    if (done < total && now - last_draw_ < std::chrono::milliseconds(100)) return;
    constexpr int kBarWidth = 30;
    const int filled = static_cast<int>(kBarWidth * done / total);
    std::fprintf(stderr, "\r[%.*s%*s] %zu/%zu %s (%zu cached) %6.1fs %s  %-40.40s", filled,
                 "##############################", kBarWidth - filled, "", done, total, unit_.c_str(), cached, elapsed,
                 eta, current.c_str());
    std::fflush(stderr);
    drew_bar_ = true;
  } else {
    const std::size_t decile = done * 10 / total;
    const bool periodic = now - last_draw_ >= std::chrono::seconds(30);
    if (decile == last_decile_ && !periodic && done != total) return;
    last_decile_ = decile;
    std::fprintf(stderr, "progress: %zu/%zu %s (%zu cached) after %.1fs, %s; last: %s\n", done, total, unit_.c_str(),
                 cached, elapsed, eta, current.c_str());
  }
  last_draw_ = now;
}

void ProgressDisplay::finish() {
  if (enabled_ && terminal_ && drew_bar_) std::fprintf(stderr, "\n");
  drew_bar_ = false;
}

}  // namespace blocklab::cli
