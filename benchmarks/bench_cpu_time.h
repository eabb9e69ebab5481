// CPU-time clocks of the encoder benchmarks: this process (CLOCK_PROCESS_CPUTIME_ID) and its waited-for children
// (getrusage RUSAGE_CHILDREN: user + system), the latter for reference encoders run as external processes; and the
// median of a round's measurements.
#pragma once

#include <sys/resource.h>

#include <algorithm>
#include <ctime>
#include <vector>

namespace blocklab {
namespace bench {

inline double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// User + system CPU time of all waited-for children so far.
inline double children_cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_CHILDREN, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

inline double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace bench
}  // namespace blocklab
