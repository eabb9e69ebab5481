// Pairwise nearest neighbour clustering (solvers/procrustes/point_clustering.h): the agglomerative first half of
// Munkberg et al. 2008 section 7.1's "pnn-clustering and the k-means algorithm". Equitz's PNN merges, at every
// step, the pair of clusters whose union raises the total weighted squared error least; for weighted means that
// increase is the Ward cost w_a w_b / (w_a + w_b) |c_a - c_b|^2. Blocks have 16 points, so a full cost matrix
// (updated in one row per merge) is both the simplest and a fast choice.
#include <algorithm>
#include <limits>

#include "core/error.h"
#include "solvers/procrustes/point_clustering.h"

namespace blocklab {

namespace {

struct ClusterSums {
  double weight = 0.0, weighted_u = 0.0, weighted_v = 0.0;
  int count = 0;
  double plain_u = 0.0, plain_v = 0.0;

  Point2 centre() const {
    // Weightless cluster (all its points have weight 0): the plain mean stands in for the undefined weighted one.
    if (!(weight > 0.0)) return {plain_u / count, plain_v / count};
    return {weighted_u / weight, weighted_v / weight};
  }
};

double merge_cost(const ClusterSums& a, const ClusterSums& b) {
  const double total = a.weight + b.weight;
  // Two weightless clusters: merging them changes no weighted error.
  if (!(total > 0.0)) return 0.0;
  const Point2 ca = a.centre(), cb = b.centre();
  const double du = ca.u - cb.u, dv = ca.v - cb.v;
  return a.weight * b.weight / total * (du * du + dv * dv);
}

// Snapshot of the current partition: clusters numbered by ascending surviving id (the lowest point index of each).
PointClustering snapshot(const std::vector<Point2>& points, const std::vector<double>& weights,
                         const std::vector<int>& root, const std::vector<char>& active) {
  const std::size_t n = points.size();
  std::vector<int> compact(n, -1);
  int cluster_count = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (active[i]) compact[i] = cluster_count++;
  PointClustering clustering;
  clustering.clusters.resize(static_cast<std::size_t>(cluster_count));
  clustering.assignment.resize(n);
  for (std::size_t i = 0; i < n; ++i) clustering.assignment[i] = compact[static_cast<std::size_t>(root[i])];
  update_cluster_statistics(points, weights, clustering);
  return clustering;
}

}  // namespace

double PointClustering::total_scatter() const {
  double total = 0.0;
  for (const WeightedCluster& cluster : clusters) total += cluster.scatter;
  return total;
}

void update_cluster_statistics(const std::vector<Point2>& points, const std::vector<double>& weights,
                               PointClustering& clustering) {
  const std::size_t cluster_count = clustering.clusters.size();
  std::vector<ClusterSums> sums(cluster_count);
  for (std::size_t i = 0; i < points.size(); ++i) {
    ClusterSums& s = sums[static_cast<std::size_t>(clustering.assignment[i])];
    s.weight += weights[i];
    s.weighted_u += weights[i] * points[i].u;
    s.weighted_v += weights[i] * points[i].v;
    s.count += 1;
    s.plain_u += points[i].u;
    s.plain_v += points[i].v;
  }
  for (std::size_t c = 0; c < cluster_count; ++c) {
    WeightedCluster& cluster = clustering.clusters[c];
    cluster.weight = sums[c].weight;
    cluster.count = sums[c].count;
    cluster.scatter = 0.0;
    // An empty cluster keeps its previous centre (k-means: a centre that lost all its points).
    if (sums[c].count > 0) cluster.centre = sums[c].centre();
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    WeightedCluster& cluster = clustering.clusters[static_cast<std::size_t>(clustering.assignment[i])];
    const double du = points[i].u - cluster.centre.u, dv = points[i].v - cluster.centre.v;
    cluster.scatter += weights[i] * (du * du + dv * dv);
  }
}

std::vector<PointClustering> pnn_cluster_levels(const std::vector<Point2>& points, const std::vector<double>& weights,
                                                int max_clusters) {
  const std::size_t n = points.size();
  if (n == 0) fail("pnn clustering", "no point to cluster");
  if (weights.size() != n) fail("pnn clustering", "one weight per point is required");
  if (max_clusters < 1) fail("pnn clustering", "max_clusters must be >= 1");
  const int top_level = static_cast<int>(std::min<std::size_t>(n, static_cast<std::size_t>(max_clusters)));

  std::vector<ClusterSums> sums(n);
  std::vector<int> root(n);         // surviving cluster id of each point
  std::vector<char> active(n, 1);
  for (std::size_t i = 0; i < n; ++i) {
    sums[i] = {weights[i], weights[i] * points[i].u, weights[i] * points[i].v, 1, points[i].u, points[i].v};
    root[i] = static_cast<int>(i);
  }
  // cost[a * n + b] for a < b, both active.
  std::vector<double> cost(n * n, 0.0);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b) cost[a * n + b] = merge_cost(sums[a], sums[b]);

  std::vector<PointClustering> levels(static_cast<std::size_t>(top_level));
  std::size_t cluster_count = n;
  if (static_cast<int>(cluster_count) <= top_level) levels[cluster_count - 1] = snapshot(points, weights, root, active);
  while (cluster_count > 1) {
    // Cheapest pair; a strictly smaller cost is needed to replace, so ties keep the lexicographically lowest pair.
    double best = std::numeric_limits<double>::infinity();
    std::size_t best_a = 0, best_b = 0;
    for (std::size_t a = 0; a < n; ++a) {
      if (!active[a]) continue;
      for (std::size_t b = a + 1; b < n; ++b) {
        if (!active[b]) continue;
        if (cost[a * n + b] < best) {
          best = cost[a * n + b];
          best_a = a;
          best_b = b;
        }
      }
    }
    // Merge b into a (a < b keeps the lowest point index as the surviving id).
    ClusterSums& merged = sums[best_a];
    const ClusterSums& absorbed = sums[best_b];
    merged.weight += absorbed.weight;
    merged.weighted_u += absorbed.weighted_u;
    merged.weighted_v += absorbed.weighted_v;
    merged.count += absorbed.count;
    merged.plain_u += absorbed.plain_u;
    merged.plain_v += absorbed.plain_v;
    active[best_b] = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (root[i] == static_cast<int>(best_b)) root[i] = static_cast<int>(best_a);
    for (std::size_t c = 0; c < n; ++c) {
      if (!active[c] || c == best_a) continue;
      const std::size_t lo = std::min(c, best_a), hi = std::max(c, best_a);
      cost[lo * n + hi] = merge_cost(sums[lo], sums[hi]);
    }
    --cluster_count;
    if (static_cast<int>(cluster_count) <= top_level) levels[cluster_count - 1] = snapshot(points, weights, root, active);
  }
  return levels;
}

}  // namespace blocklab
