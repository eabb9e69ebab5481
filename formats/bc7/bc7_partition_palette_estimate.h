// Second-stage BC7 partition estimate: the PCA line error (bc7_partition_estimate.h) plus the error of the mode's
// palette along that line. Per subset the (weighted) texels are projected on their principal axis; the palette is
// the KDFS "BPTC" index weights w_k / 64 between two continuous endpoints on the axis, fitted in one dimension:
// extremes first, then nearest indices and least-squares endpoints for them (the cluster-fit loop of Castano,
// "High Quality DXT Compression using CUDA", 2007, reduced to the axis). Endpoint quantisation is ignored.
// The line error ranks all partitions cheaply; this estimate re-ranks the best few of them, because a partition
// whose subsets lie on lines but spread over more levels than the mode's 4 or 8 palette entries can resolve is
// not a good partition for that mode (the line error alone cannot tell).
#pragma once

namespace blocklab {
namespace bc7 {

// One partition's subsets projected on their principal axes (shared by modes with the same subset count).
// Plain data without initialisers (arrays of them are cheap to declare); project_partition sets every field used.
struct PartitionProjection {
  int subset_count;
  int count[3];               // texels per subset
  float t[3][16];             // projections of the subset's texels on its unit principal axis (weighted space)
  float line_error;           // summed squared distances to the axes
};

// Projects the texels (16 x 4 lanes, 0..255; lanes with weight 0 ignored) of `partition` of `subset_count` (2, 3).
PartitionProjection project_partition(const float (&texels)[16][4], const float weights[4], int subset_count,
                                      int partition);

// line_error plus, per subset, the squared error of the best 1-D palette of 2^index_bits entries along the axis.
float palette_line_estimate(const PartitionProjection& projection, int index_bits);

}  // namespace bc7
}  // namespace blocklab
