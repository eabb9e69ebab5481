// k-means (generalised Lloyd) refinement of a clustering (solvers/procrustes/point_clustering.h): the second half
// of "Practical HDR Texture Compression" (2008) section 7.1's "pnn-clustering and the k-means algorithm [Say96]". PNN
// gives the initial centres; each iteration assigns every point to its nearest centre and moves each centre to the
// weighted mean of its points. The weighted squared error never increases, and with a fixed tie rule the result is
// deterministic.
#include "solvers/procrustes/point_clustering.h"

namespace blocklab {

void refine_with_kmeans(const std::vector<Point2>& points, const std::vector<double>& weights, int max_iterations,
                        PointClustering& clustering) {
  const std::size_t cluster_count = clustering.clusters.size();
  if (cluster_count <= 1) return;   // one cluster: nothing to reassign
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    bool changed = false;
    for (std::size_t i = 0; i < points.size(); ++i) {
      int nearest = 0;
      double nearest_distance = 0.0;
      for (std::size_t c = 0; c < cluster_count; ++c) {
        const Point2& centre = clustering.clusters[c].centre;
        const double du = points[i].u - centre.u, dv = points[i].v - centre.v;
        const double distance = du * du + dv * dv;
        // Strictly closer to replace: a point equidistant from two centres goes to the lower index.
        if (c == 0 || distance < nearest_distance) {
          nearest = static_cast<int>(c);
          nearest_distance = distance;
        }
      }
      if (clustering.assignment[i] != nearest) {
        clustering.assignment[i] = nearest;
        changed = true;
      }
    }
    if (!changed) return;   // converged: the centres are already the means of this assignment
    update_cluster_statistics(points, weights, clustering);
  }
}

}  // namespace blocklab
