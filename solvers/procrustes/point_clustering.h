// Clustering of a block's weighted 2D points into up to four groups, the correspondence step of "Practical HDR
// Texture Compression" (2008) section 7.1 ("we create up to four clusters of the chrominance points using
// pnn-clustering and the k-means algorithm [Say96]"). Two algorithms, one file each:
//   pnn_cluster_levels (pnn_clustering.cpp)  pairwise nearest neighbour (Equitz 1989; Sayood, "Introduction to Data
//                                            Compression", vector quantisation): start with one cluster per point,
//                                            repeatedly merge the pair whose merge increases the weighted squared
//                                            error least (Ward cost w_a w_b / (w_a + w_b) |c_a - c_b|^2);
//   refine_with_kmeans (kmeans_refinement.cpp) Lloyd iterations (generalised Lloyd algorithm) from given centres.
// Both are deterministic: ties go to the lowest index.
#pragma once

#include <vector>

#include "core/problem.h"

namespace blocklab {

struct WeightedCluster {
  Point2 centre;         // weighted mean of its points; the plain mean when their weights sum to 0
  double weight = 0.0;   // sum of the weights of its points
  int count = 0;         // number of points
  // Sum over its points of w_i |p_i - centre|^2 (the cluster's own share of the fitting error).
  double scatter = 0.0;
};

struct PointClustering {
  std::vector<WeightedCluster> clusters;
  std::vector<int> assignment;   // cluster index of each point
  // Sum of the clusters' scatter.
  double total_scatter() const;
};

// Partitions with 1, 2, ..., min(max_clusters, points.size()) clusters: result[k - 1] has k clusters, all nested
// (PNN is agglomerative). weights.size() == points.size(); weights >= 0. Zero-weight points merge at zero cost.
std::vector<PointClustering> pnn_cluster_levels(const std::vector<Point2>& points, const std::vector<double>& weights,
                                                int max_clusters);
// The same into `levels` (resized; the vectors of its clusterings keep their capacity, so a caller that reuses
// `levels` allocates nothing once warmed up up to 16 points, whose scratch lives on the stack).
void pnn_cluster_levels(const std::vector<Point2>& points, const std::vector<double>& weights, int max_clusters,
                        std::vector<PointClustering>& levels);
// The general implementation (pnn_clustering.cpp: each row's cheapest partner kept incrementally), which
// pnn_cluster_levels uses beyond 16 points or when a merge cost is NaN; public so that tests can check that both
// implementations give the same partitions.
void pnn_cluster_levels_row_minima(const std::vector<Point2>& points, const std::vector<double>& weights,
                                   int max_clusters, std::vector<PointClustering>& levels);

// Lloyd iterations from clustering.clusters' centres: assign each point to the nearest centre (ties: lowest
// cluster index), recompute the centres; stops when no assignment changes or after max_iterations. A cluster left
// without points keeps its previous centre with weight 0 and count 0.
void refine_with_kmeans(const std::vector<Point2>& points, const std::vector<double>& weights, int max_iterations,
                        PointClustering& clustering);

// Recomputes centres, weights, counts and scatter of `clustering` from its assignment (clusters without points
// keep their centre with weight 0).
void update_cluster_statistics(const std::vector<Point2>& points, const std::vector<double>& weights,
                               PointClustering& clustering);

}  // namespace blocklab
