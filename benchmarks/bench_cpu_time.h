// Helpers of the encoder speed benchmarks that run an external encoder side by side (bench_munkberg, bench_wang,
// bench_mavridis): one-core CPU time of this process (CLOCK_PROCESS_CPUTIME_ID) and of waited-for child processes
// (getrusage RUSAGE_CHILDREN: user + system), the median of a round's measurements, comma-separated command-line
// lists, the --repeat count and whether astcenc is installed.
#pragma once

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <sstream>
#include <string>
#include <vector>

#include "experiments/peer_encoders.h"

namespace blocklab {
namespace bench {

// The CPU clocks are the peers' (experiments/peer_encoders.h): one definition for the benchmarks and
// `blocklab bench formats`.
using blocklab::children_cpu_seconds;
using blocklab::process_cpu_seconds;

// The median of a round's measurements (the mean of the middle two for an even count).
inline double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// "a,b,c" -> {"a", "b", "c"}.
inline std::vector<std::string> split_commas(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) out.push_back(item);
  return out;
}

// True when `astcenc` (Debian package astcenc) is on the PATH; otherwise says on stderr that its rows are skipped.
inline bool astcenc_found() {
  if (std::system("command -v astcenc > /dev/null 2>&1") == 0) return true;
  std::fprintf(stderr, "astcenc not found (Debian package astcenc): astcenc rows skipped\n");
  return false;
}

// A --repeat count: an integer >= 1, or 0 when the text is not one (after saying so on stderr).
inline int parse_repeat(const char* text) {
  char* end = nullptr;
  const long value = std::strtol(text, &end, 10);
  if (end == text || *end != '\0' || value < 1 || value > 1000) {
    std::fprintf(stderr, "--repeat needs a count in [1, 1000], got '%s'\n", text);
    return 0;
  }
  return static_cast<int>(value);
}

}  // namespace bench
}  // namespace blocklab
