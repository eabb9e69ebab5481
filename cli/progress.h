// Progress display for long runs, on stderr only (stdout carries results).
// On a terminal: one bar redrawn in place, at most ~10 times a second. Otherwise (CI logs, pipes): one line at
// every 10% of the cells or every 30 seconds, whichever comes first, so logs stay short. Both show the elapsed time
// and an estimate of the time left (elapsed / done x remaining, once something is done).
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

namespace blocklab::cli {

class ProgressDisplay {
 public:
  explicit ProgressDisplay(bool enabled, std::string unit = "cells");   // unit: what is counted
  void update(std::size_t done, std::size_t total, std::size_t cached, const std::string& current);
  void finish();

 private:
  bool enabled_;
  std::string unit_;
  bool terminal_;
  bool drew_bar_ = false;
  std::size_t last_decile_ = 0;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace blocklab::cli
