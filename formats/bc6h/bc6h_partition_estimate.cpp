// Two-subset partition ranking (bc6h_partition_estimate.h).
#include "formats/bc6h/bc6h_partition_estimate.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "formats/bc7/bc7_tables.h"

namespace blocklab {
namespace bc6h {

namespace {

// Sum of squared distances of the subset's targets from their best line.
double off_line_spread(const double (&sums)[3], const double (&products)[3][3], int count) {
  if (count < 2) return 0.0;
  double covariance[3][3];
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) covariance[a][b] = products[a][b] - sums[a] * sums[b] / count;
  const double trace = covariance[0][0] + covariance[1][1] + covariance[2][2];
  double axis[3] = {1.0, 1.0, 1.0};
  double eigenvalue = 0.0;
  for (int iteration = 0; iteration < 6; ++iteration) {
    double next[3];
    for (int a = 0; a < 3; ++a) next[a] = covariance[a][0] * axis[0] + covariance[a][1] * axis[1] + covariance[a][2] * axis[2];
    const double length = std::sqrt(next[0] * next[0] + next[1] * next[1] + next[2] * next[2]);
    if (!(length > 1e-12)) return std::max(trace, 0.0);
    for (int a = 0; a < 3; ++a) axis[a] = next[a] / length;
    eigenvalue = length;
  }
  return std::max(trace - eigenvalue, 0.0);
}

}  // namespace

std::vector<int> best_partitions(const BlockTarget& block, int count) {
  std::vector<std::pair<double, int>> ranked;
  ranked.reserve(32);
  for (int partition = 0; partition < 32; ++partition) {
    const std::uint8_t* subsets = bc7::partition_subsets(2, partition);
    double sums[2][3] = {}, products[2][3][3] = {};
    int counts[2] = {0, 0};
    for (int texel = 0; texel < kTexels; ++texel) {
      const int s = subsets[texel];
      ++counts[s];
      for (int a = 0; a < 3; ++a) {
        sums[s][a] += block.target[texel][a];
        for (int b = 0; b < 3; ++b) products[s][a][b] += block.target[texel][a] * block.target[texel][b];
      }
    }
    ranked.emplace_back(off_line_spread(sums[0], products[0], counts[0]) + off_line_spread(sums[1], products[1], counts[1]),
                        partition);
  }
  std::sort(ranked.begin(), ranked.end());
  std::vector<int> best;
  for (int i = 0; i < std::min(count, 32); ++i) best.push_back(ranked[static_cast<std::size_t>(i)].second);
  return best;
}

}  // namespace bc6h
}  // namespace blocklab
