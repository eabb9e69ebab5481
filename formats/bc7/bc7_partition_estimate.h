// Cheap ranking of BC7 partitions before endpoint fitting: for every partition, the sum over its subsets of the
// squared distance of the (weighted) texels to their best-fit line (scatter trace minus largest eigenvalue, i.e.
// the PCA line error), which ignores quantisation. The encoder refits only the best few (option
// partitions_to_refine). This is the usual BC7 partition pre-selection (e.g. Castano's NVTT BC7 code and
// bc7enc estimate partitions from a line/box fit before the full search).
#pragma once

#include <cstdint>

namespace blocklab {
namespace bc7 {

// Ranks partitions 0..partition_count-1 of `subset_count` (2 or 3) subsets by estimated line error and writes the
// best min(wanted, partition_count) to ranked[], best first; returns how many. texels are 16 texels x 4 lanes
// (0..255); weights per lane (0 drops a lane). Ties keep the lower partition number first. When `ranked_errors`
// is given, the estimates of the ranked partitions are written there in the same order.
int rank_partitions(const float (&texels)[16][4], const float weights[4], int subset_count, int partition_count,
                    int wanted, int* ranked, float* ranked_errors = nullptr);

// The estimate itself for one partition (exposed for tests).
float estimate_partition_error(const float (&texels)[16][4], const float weights[4], int subset_count, int partition);

}  // namespace bc7
}  // namespace blocklab
