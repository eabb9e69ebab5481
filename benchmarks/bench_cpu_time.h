// Helpers of the encoder speed benchmarks that run an external encoder side by side (bench_munkberg, bench_wang,
// bench_mavridis, bench_bc6h, bench_bc7): one-core CPU time of this process (CLOCK_PROCESS_CPUTIME_ID) and of
// waited-for child processes (getrusage RUSAGE_CHILDREN: user + system), the median of a round's measurements and
// whether astcenc is installed. Their command line: bench_args.h.
#pragma once

#include <algorithm>
#include <cstdio>
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

// True when `astcenc` (Debian package astcenc) is on the PATH; otherwise says on stderr that its rows are skipped.
inline bool astcenc_found() {
  if (peer_tool_available("astcenc")) return true;
  std::fprintf(stderr, "astcenc not found (Debian package astcenc): astcenc rows skipped\n");
  return false;
}

}  // namespace bench
}  // namespace blocklab
