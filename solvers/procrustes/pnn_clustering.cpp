// Pairwise nearest neighbour clustering (solvers/procrustes/point_clustering.h): the agglomerative first half of
// "Practical HDR Texture Compression" (2008) section 7.1's "pnn-clustering and the k-means algorithm". Equitz's PNN
// merges, at every step, the pair of clusters whose union raises the total weighted squared error least; for weighted
// means that increase is the Ward cost w_a w_b / (w_a + w_b) |c_a - c_b|^2. Blocks have 16 points, so a full cost
// matrix (updated in one row per merge) is both the simplest and a fast choice.
//
// Two implementations of the same merge sequence (ties: the lexicographically lowest pair (a, b), a < b, of
// surviving ids):
//   * up to kSmallPnn (16) points, the block case: the cost matrix on the stack, the surviving ids in an ascending
//     list, and each row's cheapest partner kept with branch-free scans of that list (a strictly smaller cost
//     replaces), so a merge costs O(n) instead of a scan of all O(n^2) surviving pairs;
//   * otherwise, or when a merge cost is NaN (only reachable with weights near the overflow limit): each row keeps
//     its cheapest partner, updated incrementally. For costs without NaN both find the lexicographically first
//     cheapest pair, i.e. the same merges and the same partitions (tests/unit/test_procrustes.cpp compares them on
//     random weighted point sets); a NaN makes the row-wise order observable, so that case always takes the
//     row-wise path, whose NaN behaviour is the reference.
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

  // Merges another cluster's sums into this one (the one addition order both PNN implementations use).
  void absorb(const ClusterSums& other) {
    weight += other.weight;
    weighted_u += other.weighted_u;
    weighted_v += other.weighted_v;
    count += other.count;
    plain_u += other.plain_u;
    plain_v += other.plain_v;
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

// Working state of one row-wise PNN run. Local to the run: the row-wise path serves point sets beyond kSmallPnn
// points and NaN costs only (a block's 16 points take the stack-based scan), so its allocations are not on the
// per-block path.
struct PnnScratch {
  std::vector<PnnCluster> clusters;
  std::vector<int> root;              // surviving cluster id of each point
  std::vector<char> active;
  std::vector<double> cost;           // cost[a * n + b] for a < b, both active
  std::vector<std::size_t> partner;   // cheapest partner b > a of row a (n = none)
  std::vector<double> partner_cost;   // cost[a * n + partner[a]], cached
  std::vector<int> compact;           // snapshot numbering
};

// Snapshot of the current partition into `clustering` (its vectors' capacity is reused): clusters numbered by
// ascending surviving id (the lowest point index of each).
void snapshot(const std::vector<Point2>& points, const std::vector<double>& weights, PnnScratch& s,
              PointClustering& clustering) {
  const std::size_t n = points.size();
  int cluster_count = 0;
  for (std::size_t i = 0; i < n; ++i) s.compact[i] = s.active[i] ? cluster_count++ : -1;
  clustering.clusters.assign(static_cast<std::size_t>(cluster_count), WeightedCluster{});
  clustering.assignment.resize(n);
  for (std::size_t i = 0; i < n; ++i) clustering.assignment[i] = s.compact[static_cast<std::size_t>(s.root[i])];
  update_cluster_statistics(points, weights, clustering);
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

// The row-wise implementation (file comment): any point count, any costs.
void pnn_cluster_levels_row_minima(const std::vector<Point2>& points, const std::vector<double>& weights,
                                   int max_clusters, std::vector<PointClustering>& levels) {
  const std::size_t n = points.size();
  if (n == 0) fail("pnn clustering", "no point to cluster");
  if (weights.size() != n) fail("pnn clustering", "one weight per point is required");
  if (max_clusters < 1) fail("pnn clustering", "max_clusters must be >= 1");
  const int top_level = static_cast<int>(std::min<std::size_t>(n, static_cast<std::size_t>(max_clusters)));
  PnnScratch s;
  s.clusters.resize(n);
  s.root.resize(n);
  s.active.assign(n, 1);
  s.compact.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    s.clusters[i].sums = {weights[i], weights[i] * points[i].u, weights[i] * points[i].v, 1, points[i].u, points[i].v};
    s.clusters[i].centre = s.clusters[i].sums.centre();
    s.root[i] = static_cast<int>(i);
  }
  // cost[a * n + b] for a < b, both active. Each row a keeps its cheapest partner b > a (`partner[a]`, ties: the
  // lowest b; n = none), so the cheapest pair overall is the cheapest row minimum (ties: the lowest a): the same
  // pair as a scan of all pairs in lexicographic order, found in O(n) instead of O(n^2) per merge. Entries with
  // a >= b are never read.
  s.cost.resize(n * n);
  double* const cost = s.cost.data();
  const PnnCluster* const clusters = s.clusters.data();
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b) cost[a * n + b] = merge_cost(clusters[a], clusters[b]);
  s.partner.resize(n);
  s.partner_cost.resize(n);
  std::size_t* const partner = s.partner.data();
  double* const partner_cost = s.partner_cost.data();
  const char* const active = s.active.data();
  const auto rescan_row = [&](std::size_t a) {
    std::size_t best = n;
    double best_cost = 0.0;
    const double* row = cost + a * n;
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

  levels.resize(static_cast<std::size_t>(top_level));
  std::size_t cluster_count = n;
  if (static_cast<int>(cluster_count) <= top_level) snapshot(points, weights, s, levels[cluster_count - 1]);
  while (cluster_count > 1) {
    // Cheapest pair; a strictly smaller cost is needed to replace, so ties keep the lexicographically lowest pair.
    std::size_t best_a = n;
    for (std::size_t a = 0; a < n; ++a) {
      if (!active[a] || partner[a] == n) continue;
      if (best_a == n || partner_cost[a] < partner_cost[best_a]) best_a = a;
    }
    const std::size_t best_b = partner[best_a];
    // Merge b into a (a < b keeps the lowest point index as the surviving id).
    ClusterSums& merged = s.clusters[best_a].sums;
    const ClusterSums& absorbed = s.clusters[best_b].sums;
    merged.absorb(absorbed);
    s.clusters[best_a].centre = merged.centre();
    s.active[best_b] = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (s.root[i] == static_cast<int>(best_b)) s.root[i] = static_cast<int>(best_a);
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
    if (static_cast<int>(cluster_count) <= top_level) snapshot(points, weights, s, levels[cluster_count - 1]);
  }
}

namespace {

constexpr std::size_t kSmallPnn = 16;

// The full-scan implementation for n <= kSmallPnn points (file comment). Returns false, with `levels` unspecified,
// as soon as a merge cost is NaN (the caller then runs pnn_cluster_levels_row_minima).
bool pnn_levels_small(const std::vector<Point2>& points, const std::vector<double>& weights, int top_level,
                      std::vector<PointClustering>& levels) {
  const std::size_t n = points.size();
  std::array<PnnCluster, kSmallPnn> clusters;
  std::array<int, kSmallPnn> root{};       // surviving id of each point's cluster
  std::array<int, kSmallPnn> survivors{};  // surviving ids, ascending
  double cost[kSmallPnn][kSmallPnn];       // cost[a][b] for surviving a < b; other entries are never read
  for (std::size_t i = 0; i < n; ++i) {
    clusters[i].sums = {weights[i], weights[i] * points[i].u, weights[i] * points[i].v, 1, points[i].u, points[i].v};
    clusters[i].centre = clusters[i].sums.centre();
    root[i] = static_cast<int>(i);
    survivors[i] = static_cast<int>(i);
  }
  bool nan = false;
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b) {
      cost[a][b] = merge_cost(clusters[a], clusters[b]);
      nan |= cost[a][b] != cost[a][b];
    }
  if (nan) return false;

  // Snapshot: clusters numbered by their rank among the surviving ids (ascending, as the row-wise snapshot).
  const auto take_snapshot = [&](std::size_t count, PointClustering& clustering) {
    std::array<int, kSmallPnn> compact{};
    for (std::size_t r = 0; r < count; ++r) compact[static_cast<std::size_t>(survivors[r])] = static_cast<int>(r);
    clustering.clusters.assign(count, WeightedCluster{});
    clustering.assignment.resize(n);
    for (std::size_t i = 0; i < n; ++i) clustering.assignment[i] = compact[static_cast<std::size_t>(root[i])];
    update_cluster_statistics(points, weights, clustering);
  };

  // Each surviving row a keeps its cheapest partner b > a among the survivors (row_partner; ties: the lowest b) and
  // that cost (row_min). The lexicographically first cheapest pair is then the cheapest row minimum (ties: the lowest
  // a): the pair a scan of all surviving pairs in (a, b) order finds, in O(n) per merge. No cost is NaN here, so `<`
  // is a total preorder. Rows are indexed by id; `ra` is a rank in `survivors`.
  std::array<double, kSmallPnn> row_min{};
  std::array<int, kSmallPnn> row_partner{};
  std::size_t count = n;
  const auto rescan_row = [&](std::size_t ra) {   // ra + 1 < count: the row has a partner
    const double* row = cost[survivors[ra]];
    int best = survivors[ra + 1];
    double best_cost = row[best];
    for (std::size_t rb = ra + 2; rb < count; ++rb) {
      const double c = row[survivors[rb]];
      const bool cheaper = c < best_cost;
      best_cost = cheaper ? c : best_cost;
      best = cheaper ? survivors[rb] : best;
    }
    row_min[static_cast<std::size_t>(survivors[ra])] = best_cost;
    row_partner[static_cast<std::size_t>(survivors[ra])] = best;
  };
  for (std::size_t ra = 0; ra + 1 < count; ++ra) rescan_row(ra);

  levels.resize(static_cast<std::size_t>(top_level));
  if (static_cast<int>(count) <= top_level) take_snapshot(count, levels[count - 1]);
  while (count > 1) {
    // The cheapest row minimum over the rows that have a partner (every survivor but the last), strictly cheaper
    // replaces.
    std::size_t best_ra = 0;
    double best_cost = row_min[static_cast<std::size_t>(survivors[0])];
    for (std::size_t ra = 1; ra + 1 < count; ++ra) {
      const double c = row_min[static_cast<std::size_t>(survivors[ra])];
      const bool cheaper = c < best_cost;
      best_cost = cheaper ? c : best_cost;
      best_ra = cheaper ? ra : best_ra;
    }
    const int a = survivors[best_ra], b = row_partner[static_cast<std::size_t>(a)];
    // Merge b into a (a < b keeps the lowest point index as the surviving id); sums in the row-wise order.
    ClusterSums& merged = clusters[static_cast<std::size_t>(a)].sums;
    const ClusterSums& absorbed = clusters[static_cast<std::size_t>(b)].sums;
    merged.absorb(absorbed);
    clusters[static_cast<std::size_t>(a)].centre = merged.centre();
    for (std::size_t i = 0; i < n; ++i) root[i] = root[i] == b ? a : root[i];
    std::size_t rb = best_ra + 1;
    while (survivors[rb] != b) ++rb;
    for (std::size_t r = rb; r + 1 < count; ++r) survivors[r] = survivors[r + 1];
    --count;
    for (std::size_t r = 0; r < count; ++r) {
      const int c = survivors[r];
      if (c == a) continue;
      const int lo = std::min(a, c), hi = std::max(a, c);
      const double updated = merge_cost(clusters[static_cast<std::size_t>(lo)], clusters[static_cast<std::size_t>(hi)]);
      cost[lo][hi] = updated;
      nan |= updated != updated;
    }
    if (nan) return false;
    // Row minima that may have changed: row a (all its costs changed); rows whose partner was a or b (rescanned);
    // rows c < a, whose cost to a changed (a new minimum only if cheaper than the kept one, or equal with a lower id).
    // Rows c > a other than those keep every cost they had except b's.
    for (std::size_t r = 0; r + 1 < count; ++r) {
      const int c = survivors[r];
      const int partner = row_partner[static_cast<std::size_t>(c)];
      if (c == a || partner == a || partner == b) {
        rescan_row(r);
      } else if (c < a) {
        const double to_a = cost[c][a], kept = row_min[static_cast<std::size_t>(c)];
        // The equal case keeps the invariant (lowest partner among ties). In exact arithmetic it cannot arise: by
        // Ward's reducibility the merged cost is >= min(cost to a, cost to b) >= the kept minimum, with equality only
        // when all three are equal, and then a (< b, < partner) would already have been the partner.
        if (to_a < kept || (to_a == kept && a < partner)) {
          row_min[static_cast<std::size_t>(c)] = to_a;
          row_partner[static_cast<std::size_t>(c)] = a;
        }
      }
    }
    if (static_cast<int>(count) <= top_level) take_snapshot(count, levels[count - 1]);
  }
  return true;
}

}  // namespace

void pnn_cluster_levels(const std::vector<Point2>& points, const std::vector<double>& weights, int max_clusters,
                        std::vector<PointClustering>& levels) {
  const std::size_t n = points.size();
  if (n == 0) fail("pnn clustering", "no point to cluster");
  if (weights.size() != n) fail("pnn clustering", "one weight per point is required");
  if (max_clusters < 1) fail("pnn clustering", "max_clusters must be >= 1");
  const int top_level = static_cast<int>(std::min<std::size_t>(n, static_cast<std::size_t>(max_clusters)));
  if (n <= kSmallPnn && pnn_levels_small(points, weights, top_level, levels)) return;
  pnn_cluster_levels_row_minima(points, weights, max_clusters, levels);
}

std::vector<PointClustering> pnn_cluster_levels(const std::vector<Point2>& points, const std::vector<double>& weights,
                                                int max_clusters) {
  std::vector<PointClustering> levels;
  pnn_cluster_levels(points, weights, max_clusters, levels);
  return levels;
}

}  // namespace blocklab
