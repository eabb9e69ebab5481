// Progress display for long runs, on stderr only (stdout carries results).
// On a terminal: one bar redrawn in place, at most ~10 times a second. Otherwise (CI logs, batch jobs, pipes): one
// line per cell computed, and one when the run ends. Both show the time so far and an ETA: the mean wall time per
// cell finished since the first computed cell started (cached cells cost nothing), times the cells left; under MPI
// the ranks' cells finish in parallel, so the same ratio measures the whole job's rate.
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

namespace blocklab::cli {

// "42s", "2m13s", "1h05m".
std::string duration_text(double seconds);

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
  bool computing_ = false;        // a computed (not cached) cell has started
  std::chrono::steady_clock::time_point start_, last_draw_, compute_start_;
};

}  // namespace blocklab::cli
