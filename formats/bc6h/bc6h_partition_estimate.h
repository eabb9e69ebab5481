// Ranking of the 32 BC6H two-subset partitions by an estimate of their error: for each subset, the spread of its
// targets off their principal line (trace of the covariance minus its largest eigenvalue, by power iteration) in the
// interpolation domain (bc6h_endpoint_fit.h). A partition whose two regions each lie near a line fits a two-subset
// mode well; the mode search fully fits only the best few.
#pragma once

#include <vector>

#include "formats/bc6h/bc6h_endpoint_fit.h"

namespace blocklab {
namespace bc6h {

// The `count` partitions (0..31) with the lowest estimates, best first (ties: lower partition number first).
std::vector<int> best_partitions(const BlockTarget& block, int count);

}  // namespace bc6h
}  // namespace blocklab
