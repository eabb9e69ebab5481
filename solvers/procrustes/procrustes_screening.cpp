// The screened candidate search of the `procrustes` solver (solvers/procrustes/procrustes_screening.h;
// "Practical HDR Texture Compression" (2008) section 7.1, eqs. 11-15, and the stretched error of section 7.2).
#include "solvers/procrustes/procrustes_screening.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace blocklab {

namespace {

constexpr int kCoordinates = 2 * kFitLandmarkCount;

// The refinement measure of RefineMeasure, evaluated with StretchTable (file comment of the header, step 4).
struct ScreenModel {
  std::size_t n = 0;
  const double* tu = nullptr;   // mapped targets, u then v
  const double* tv = nullptr;
  const double* w = nullptr;
  std::array<std::array<double, 4>, kCoordinates> rows{};
  RefineMeasure measure;   // the stretch (StretchTable) and its slope

  // Error at x (RefineMeasure), the nearest landmark of each point (ties: the lower landmark) and each landmark
  // coordinate's raw and mapped value. Early exit: once the partial sum is >= `limit` (checked every 4 points) the
  // partial sum is returned and `nearest` is incomplete; every term is >= 0, so the full error is >= it too. A NaN
  // also returns at once (it compares as "not below the limit", like the full error would).
  double error(const double* x, double limit, int* nearest, double* raw, double* mapped) const {
    for (int j = 0; j < kCoordinates; ++j) {
      const auto& r = rows[static_cast<std::size_t>(j)];
      raw[j] = r[0] * x[0] + r[1] * x[1] + r[2] * x[2] + r[3] * x[3];
      mapped[j] = measure.map(std::min(std::max(raw[j], 0.0), 1.0));
    }
    // No limit: the loop without the exit test (the same sum, in the same order).
    return limit == std::numeric_limits<double>::infinity() ? point_sum<false>(limit, nearest, mapped)
                                                            : point_sum<true>(limit, nearest, mapped);
  }

  template <bool kEarlyExit>
  double point_sum(double limit, int* nearest, const double* mapped) const {
    double sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      double best = 0.0;
      int k_best = 0;
      for (int k = 0; k < kFitLandmarkCount; ++k) {
        const double du = tu[i] - mapped[2 * k], dv = tv[i] - mapped[2 * k + 1];
        const double d = du * du + dv * dv;
        const bool closer = k == 0 || d < best;   // strictly closer replaces: ties go to the lower landmark
        best = closer ? d : best;
        k_best = closer ? k : k_best;
      }
      nearest[i] = k_best;
      sum += w[i] * best;
      if (kEarlyExit && (i & 3u) == 3u && !(sum < limit)) return sum;
    }
    return sum;
  }
};

// One refinement state: base points (in the box), error, and what `ScreenModel::error` reported at them.
using State = ScreenedStart;

// Projected Gauss-Newton (procrustes_refinement.h, with every step clamped to the box [0, 1]^4 before its error
// is measured); `nearest` holds the assignment at s.x and `scratch` is the trial's. A step is kept only if it lowers
// the error (the trial's error sum exits early once it reaches the current error).
void refine_in_box(const ScreenModel& model, int iterations, State& s, std::vector<int>& nearest,
                   std::vector<int>& scratch) {
  const double* w = model.w;
  for (int iteration = 0; iteration < iterations; ++iteration) {
    double coordinate_weight[kCoordinates] = {}, coordinate_residual[kCoordinates] = {};
    for (std::size_t i = 0; i < model.n; ++i) {
      if (!(w[i] > 0.0)) continue;   // weightless points constrain nothing
      const int j = 2 * nearest[i];
      coordinate_weight[j] += w[i];
      coordinate_weight[j + 1] += w[i];
      coordinate_residual[j] += w[i] * (model.tu[i] - s.mapped[j]);
      coordinate_residual[j + 1] += w[i] * (model.tv[i] - s.mapped[j + 1]);
    }
    double rhs[4];
    if (!landmark_gauss_newton_step(coordinate_weight, coordinate_residual, s.raw, s.mapped, model.measure, model.rows,
                                    rhs))
      break;
    State next;
    for (int p = 0; p < 4; ++p) next.x[p] = std::min(std::max(s.x[p] + rhs[p], 0.0), 1.0);
    next.error = model.error(next.x, s.error, scratch.data(), next.raw, next.mapped);
    if (!(next.error < s.error)) break;   // no progress (or NaN): keep the better x
    s = next;
    nearest.swap(scratch);
  }
}

// Inserts (error, index) into the ascending list `best` of at most `limit` entries; a strictly smaller error is
// needed to pass an equal one, so equal errors keep the earlier index.
void insert_best(std::vector<std::pair<double, std::size_t>>& best, std::size_t limit, double error,
                 std::size_t index) {
  if (limit == 0) return;
  if (best.size() == limit && !(error < best.back().first)) return;
  // Full: the last entry drops out (its slot is overwritten); else the list grows by one.
  std::size_t j = best.size() == limit ? limit - 1 : best.size();
  if (best.size() < limit) best.emplace_back(error, index);
  for (; j > 0 && error < best[j - 1].first; --j) best[j] = best[j - 1];
  best[j] = {error, index};
}

// The current admission limit of a top list: the last entry's error once full, else +infinity.
double admission(const std::vector<std::pair<double, std::size_t>>& best, std::size_t limit) {
  return best.size() == limit ? best.back().first : std::numeric_limits<double>::infinity();
}

// The snap of procrustes_solver.cpp step 4: clamp to the bounds, then the nearest lattice point (if any).
double snap(const Problem& problem, int p, double value) {
  const double clamped = std::min(std::max(value, problem.lower(p)), problem.upper(p));
  const Lattice& lattice = problem.lattice(p);
  return lattice.present() ? lattice.point(lattice.nearest_index(clamped)) : clamped;
}

}  // namespace

std::vector<ProcrustesCandidate> screen_procrustes_candidates(const Problem& problem,
                                                              const std::vector<double>& targets,
                                                              const std::vector<double>& weights,
                                                              const RefineMeasure& measure,
                                                              const LandmarkCoefficients& landmarks,
                                                              const std::vector<ProcrustesCandidate>& candidates,
                                                              const std::vector<PointClustering>& levels,
                                                              int screened, int refined, int iterations,
                                                              int evaluated, ScreeningBuffers& buffers) {
  ScreenModel model;
  model.n = weights.size();
  model.tu = targets.data();
  model.tv = targets.data() + model.n;
  model.w = weights.data();
  model.measure = measure;
  model.rows = landmark_rows(landmarks);
  std::vector<int>& nearest = buffers.nearest;
  std::vector<int>& scratch = buffers.scratch;
  nearest.resize(model.n);
  scratch.resize(model.n);

  // 2. Screening: the `kept` lowest start errors among the first `screen_count` candidates (exact top list with
  //    early exit). Kept: the refined ones, or without refinement the evaluated ones (0: all screened).
  const std::size_t screen_count =
      screened == 0 ? candidates.size() : std::min(candidates.size(), static_cast<std::size_t>(screened));
  const bool refining = refined > 0 && iterations > 0;
  std::size_t kept = static_cast<std::size_t>(refining ? refined : evaluated);
  if (kept == 0 || kept > screen_count) kept = screen_count;
  std::vector<std::pair<double, std::size_t>>& best_start = buffers.best_start;
  best_start.clear();
  const auto boxed = [](const ProcrustesCandidate& c, double* x) {
    const double ideal[4] = {c.base0.u, c.base0.v, c.base1.u, c.base1.v};
    for (int p = 0; p < 4; ++p) x[p] = std::min(std::max(ideal[p], 0.0), 1.0);   // 1. onto the box
  };
  // Cluster summaries on the measure: per level and cluster, total weight and weighted mean of the mapped points,
  // and per level the mapped scatter sum_i w_i |t_i - mean of its cluster|^2.
  struct Summary {
    double weight = 0.0, u = 0.0, v = 0.0;
  };
  std::array<std::array<Summary, kFitLandmarkCount>, kFitLandmarkCount> summaries{};
  std::array<double, kFitLandmarkCount> level_scatter{};
  std::array<int, kFitLandmarkCount> level_clusters{};
  const std::size_t level_count = std::min(levels.size(), static_cast<std::size_t>(kFitLandmarkCount));
  for (std::size_t l = 0; l < level_count; ++l) {
    const PointClustering& level = levels[l];
    const int clusters = static_cast<int>(std::min(level.clusters.size(), static_cast<std::size_t>(kFitLandmarkCount)));
    level_clusters[l] = clusters;
    auto& sum = summaries[l];
    for (std::size_t i = 0; i < model.n; ++i) {
      Summary& c = sum[static_cast<std::size_t>(level.assignment[i])];
      c.weight += model.w[i];
      c.u += model.w[i] * model.tu[i];
      c.v += model.w[i] * model.tv[i];
    }
    for (int c = 0; c < clusters; ++c) {
      Summary& cluster = sum[static_cast<std::size_t>(c)];
      // A weightless cluster contributes nothing (its mean is never read).
      if (cluster.weight > 0.0) {
        cluster.u /= cluster.weight;
        cluster.v /= cluster.weight;
      }
    }
    double scatter = 0.0;
    for (std::size_t i = 0; i < model.n; ++i) {
      const Summary& c = sum[static_cast<std::size_t>(level.assignment[i])];
      const double du = model.tu[i] - c.u, dv = model.tv[i] - c.v;
      scatter += model.w[i] * (du * du + dv * dv);
    }
    level_scatter[l] = scatter;
  }
  for (std::size_t c = 0; c < screen_count; ++c) {
    State s;
    boxed(candidates[c], s.x);
    const int level = candidates[c].level;
    double error;
    if (level >= 1 && static_cast<std::size_t>(level) <= level_count) {
      // Start error estimated at the cluster level: each cluster mean to its nearest mapped landmark, plus the
      // level's scatter (exact when every point keeps its cluster's landmark).
      for (int j = 0; j < kCoordinates; ++j) {
        const auto& r = model.rows[static_cast<std::size_t>(j)];
        s.raw[j] = r[0] * s.x[0] + r[1] * s.x[1] + r[2] * s.x[2] + r[3] * s.x[3];
        s.mapped[j] = model.measure.map(std::min(std::max(s.raw[j], 0.0), 1.0));
      }
      const std::size_t l = static_cast<std::size_t>(level - 1);
      error = level_scatter[l];
      for (int k = 0; k < level_clusters[l]; ++k) {
        const Summary& cluster = summaries[l][static_cast<std::size_t>(k)];
        if (!(cluster.weight > 0.0)) continue;
        double best = 0.0;
        for (int m = 0; m < kFitLandmarkCount; ++m) {
          const double du = cluster.u - s.mapped[2 * m], dv = cluster.v - s.mapped[2 * m + 1];
          const double d = du * du + dv * dv;
          best = m == 0 || d < best ? d : best;
        }
        error += cluster.weight * best;
      }
    } else {
      const double limit = admission(best_start, kept);
      error = model.error(s.x, limit, nearest.data(), s.raw, s.mapped);
    }
    const double limit = admission(best_start, kept);
    if (error < limit) insert_best(best_start, kept, error, c);
  }

  // Refinement of the kept ones in start-error order; a start whose assignment and clamp pattern repeats an
  // earlier one's takes the same step (procrustes_refinement.h, "Duplicates") and is dropped.
  std::vector<State>& states = buffers.states;
  std::vector<std::uint64_t>& seen = buffers.seen;
  states.clear();
  seen.clear();
  for (const auto& entry : best_start) {
    State s;
    boxed(candidates[entry.second], s.x);
    s.error = model.error(s.x, std::numeric_limits<double>::infinity(), nearest.data(), s.raw, s.mapped);
    if (refining) {
      std::uint64_t key = 0;
      for (int j = 0; j < kCoordinates; ++j) key = key << 2 | (s.raw[j] < 0.0 ? 1u : s.raw[j] > 1.0 ? 2u : 0u);
      for (std::size_t i = 0; i < model.n; ++i)
        key = model.n <= 24 ? key << 2 | static_cast<std::uint64_t>(nearest[i])
                            : (key ^ static_cast<std::uint64_t>(nearest[i] + 1)) * 0x100000001b3ull;
      if (std::find(seen.begin(), seen.end(), key) != seen.end()) continue;
      seen.push_back(key);
      refine_in_box(model, iterations, s, nearest, scratch);
    }
    states.push_back(s);
  }

  // 3. Choice: the measured error at each snapped point; the best `evaluated` distinct snapped points go on.
  const std::size_t chosen_limit = evaluated == 0 ? states.size() : static_cast<std::size_t>(evaluated);
  std::vector<std::pair<double, std::size_t>>& best_snapped = buffers.best_snapped;
  std::vector<std::array<double, kLandmarkFitParameterCount>>& snapped = buffers.snapped;
  best_snapped.clear();
  snapped.clear();
  for (std::size_t c = 0; c < states.size(); ++c) {
    std::array<double, kLandmarkFitParameterCount> y{};
    for (int p = 0; p < 4; ++p) y[static_cast<std::size_t>(p)] = snap(problem, p, states[c].x[p]);
    snapped.push_back(y);
    bool repeated = false;   // the same stored point as an earlier candidate: same error, never strictly better
    for (std::size_t d = 0; d < c && !repeated; ++d) repeated = snapped[d] == y;
    if (repeated) continue;
    State probe;
    const double limit = admission(best_snapped, chosen_limit);
    const double error = model.error(y.data(), limit, scratch.data(), probe.raw, probe.mapped);
    if (error < limit) insert_best(best_snapped, chosen_limit, error, c);
  }
  std::vector<ProcrustesCandidate> out;
  out.reserve(best_snapped.size());
  for (const auto& entry : best_snapped) {
    const State& s = states[entry.second];
    ProcrustesCandidate candidate;
    candidate.error_bound = entry.first;   // here: the measured error at the snapped point
    candidate.base0 = {s.x[0], s.x[1]};
    candidate.base1 = {s.x[2], s.x[3]};
    out.push_back(candidate);
  }
  return out;
}

}  // namespace blocklab
