// Pairwise nearest neighbour clustering (solvers/procrustes/point_clustering.h): the agglomerative first half of
// Munkberg et al. 2008 section 7.1's "pnn-clustering and the k-means algorithm". Equitz's PNN merges, at every
// step, the pair of clusters whose union raises the total weighted squared error least; for weighted means that
// increase is the Ward cost w_a w_b / (w_a + w_b) |c_a - c_b|^2. Blocks have 16 points, so a full cost matrix
// (updated in one row per merge) is both the simplest and a fast choice.
#include <algorithm>
#include <array>
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

// A cluster's sums and its centre, cached (the centre is read by every merge cost of the cluster).
struct PnnCluster {
  ClusterSums sums;
  Point2 centre;
};

double merge_cost(const PnnCluster& a, const PnnCluster& b) {
  const double total = a.sums.weight + b.sums.weight;
  // Two weightless clusters: merging them changes no weighted error.
  if (!(total > 0.0)) return 0.0;
  const double du = a.centre.u - b.centre.u, dv = a.centre.v - b.centre.v;
  return a.sums.weight * b.sums.weight / total * (du * du + dv * dv);
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
  // Up to 4 clusters (every use in the procrustes solver) the sums live on the stack: this runs once per k-means
  // iteration and level, and a heap allocation costs as much as the sums themselves.
  std::array<ClusterSums, 4> small_sums{};
  std::vector<ClusterSums> large_sums(cluster_count > small_sums.size() ? cluster_count : 0);
  ClusterSums* sums = cluster_count > small_sums.size() ? large_sums.data() : small_sums.data();
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

  std::vector<PnnCluster> clusters(n);
  std::vector<int> root(n);         // surviving cluster id of each point
  std::vector<char> active(n, 1);
  for (std::size_t i = 0; i < n; ++i) {
    clusters[i].sums = {weights[i], weights[i] * points[i].u, weights[i] * points[i].v, 1, points[i].u, points[i].v};
    clusters[i].centre = clusters[i].sums.centre();
    root[i] = static_cast<int>(i);
  }
  // cost[a * n + b] for a < b, both active. Each row a keeps its cheapest partner b > a (`partner[a]`, ties: the
  // lowest b; n = none), so the cheapest pair overall is the cheapest row minimum (ties: the lowest a): the same
  // pair as a scan of all pairs in lexicographic order, found in O(n) instead of O(n^2) per merge.
  std::vector<double> cost(n * n, 0.0);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b) cost[a * n + b] = merge_cost(clusters[a], clusters[b]);
  std::vector<std::size_t> partner(n, n);
  std::vector<double> partner_cost(n, 0.0);   // cost[a * n + partner[a]], cached
  const auto rescan_row = [&](std::size_t a) {
    std::size_t best = n;
    double best_cost = 0.0;
    const double* row = cost.data() + a * n;
    for (std::size_t b = a + 1; b < n; ++b) {
      // The first active b is taken whatever its cost (also a NaN one); later ones must be strictly cheaper.
      if (active[b] && (best == n || row[b] < best_cost)) {
        best = b;
        best_cost = row[b];
      }
    }
    partner[a] = best;
    partner_cost[a] = best_cost;
  };
  for (std::size_t a = 0; a < n; ++a) rescan_row(a);

  std::vector<PointClustering> levels(static_cast<std::size_t>(top_level));
  std::size_t cluster_count = n;
  if (static_cast<int>(cluster_count) <= top_level) levels[cluster_count - 1] = snapshot(points, weights, root, active);
  while (cluster_count > 1) {
    // Cheapest pair; a strictly smaller cost is needed to replace, so ties keep the lexicographically lowest pair.
    std::size_t best_a = n;
    for (std::size_t a = 0; a < n; ++a) {
      if (!active[a] || partner[a] == n) continue;
      if (best_a == n || partner_cost[a] < partner_cost[best_a]) best_a = a;
    }
    const std::size_t best_b = partner[best_a];
    // Merge b into a (a < b keeps the lowest point index as the surviving id).
    ClusterSums& merged = clusters[best_a].sums;
    const ClusterSums& absorbed = clusters[best_b].sums;
    merged.weight += absorbed.weight;
    merged.weighted_u += absorbed.weighted_u;
    merged.weighted_v += absorbed.weighted_v;
    merged.count += absorbed.count;
    merged.plain_u += absorbed.plain_u;
    merged.plain_v += absorbed.plain_v;
    clusters[best_a].centre = merged.centre();
    active[best_b] = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (root[i] == static_cast<int>(best_b)) root[i] = static_cast<int>(best_a);
    for (std::size_t c = 0; c < n; ++c) {
      if (!active[c] || c == best_a) continue;
      const std::size_t lo = std::min(c, best_a), hi = std::max(c, best_a);
      cost[lo * n + hi] = merge_cost(clusters[lo], clusters[hi]);
    }
    // Row minima that may have changed: row a (all its costs changed), rows whose partner was a or b (rescanned),
    // and rows c < a, whose cost to a changed (a new minimum only if it beats the kept one; ties: the lower index).
    rescan_row(best_a);
    for (std::size_t c = 0; c < n; ++c) {
      if (!active[c] || c == best_a) continue;
      if (partner[c] == best_a || partner[c] == best_b) {
        rescan_row(c);
      } else if (c < best_a && partner[c] != n) {
        const double to_a = cost[c * n + best_a], kept = partner_cost[c];
        if (to_a < kept || (to_a == kept && best_a < partner[c])) {
          partner[c] = best_a;
          partner_cost[c] = to_a;
        }
      } else if (c < best_a) {
        partner[c] = best_a;   // a was its only remaining partner candidate
        partner_cost[c] = cost[c * n + best_a];
      }
    }
    --cluster_count;
    if (static_cast<int>(cluster_count) <= top_level) levels[cluster_count - 1] = snapshot(points, weights, root, active);
  }
  return levels;
}

}  // namespace blocklab
