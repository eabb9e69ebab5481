// Clamp-aware refinement of a Procrustes candidate (solvers/procrustes/procrustes_refinement.h; "Practical HDR Texture
// Compression" (2008) section 7.1, eqs. 12-15, with the clamp of decoded landmarks and the stretch of section 7.2).
#include "solvers/procrustes/procrustes_refinement.h"

#include <array>

namespace blocklab {

namespace {



// Error (see RefineMeasure) at x, the nearest mapped landmark of each point (ties: the lower landmark) and each
// landmark coordinate's raw (unclamped) and mapped (clamped, then mapped) value. `targets` holds the mapped
// points' u values, then their v values.
double measured_error(const std::vector<double>& targets, const std::vector<double>& weights,
                      const RefineMeasure& measure,
                      const std::array<std::array<double, 4>, 2 * kFitLandmarkCount>& rows, const double* x,
                      std::vector<int>& nearest, double* raw, double* mapped) {
  for (int j = 0; j < 2 * kFitLandmarkCount; ++j) {
    const auto& r = rows[static_cast<std::size_t>(j)];
    raw[j] = r[0] * x[0] + r[1] * x[1] + r[2] * x[2] + r[3] * x[3];
    mapped[j] = measure.map(std::min(std::max(raw[j], 0.0), 1.0));
  }
  // Structure of arrays (targets[0 .. n) = u, targets[n .. 2n) = v) and branch-free selects, so the compiler can
  // vectorise the loop over points.
  const std::size_t n = weights.size();
  const double* tu = targets.data();
  const double* tv = targets.data() + n;
  double error = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    double best = 0.0;
    int k_best = 0;
    for (int k = 0; k < kFitLandmarkCount; ++k) {
      const double du = tu[i] - mapped[2 * k], dv = tv[i] - mapped[2 * k + 1];
      const double d = du * du + dv * dv;
      // Strictly closer to replace: ties go to the lower landmark.
      const bool closer = k == 0 || d < best;
      best = closer ? d : best;
      k_best = closer ? k : k_best;
    }
    nearest[i] = k_best;
    error += weights[i] * best;
  }
  return error;
}

}  // namespace

LandmarkRows landmark_rows(const LandmarkCoefficients& landmarks) {
  // u = (1 - a) u0 + b v0 + a u1 - b v1, v = -b u0 + (1 - a) v0 + b u1 + a v1 (core/problem.h).
  LandmarkRows rows;
  for (int k = 0; k < kFitLandmarkCount; ++k) {
    const double a = landmarks.along(k), b = landmarks.across(k);
    rows[static_cast<std::size_t>(2 * k)] = {1.0 - a, b, a, -b};
    rows[static_cast<std::size_t>(2 * k + 1)] = {-b, 1.0 - a, b, a};
  }
  return rows;
}

bool solve4(double (&a)[4][4], double (&b)[4]) {
  for (int c = 0; c < 4; ++c) {
    int pivot = c;
    for (int r = c + 1; r < 4; ++r)
      if (std::abs(a[r][c]) > std::abs(a[pivot][c])) pivot = r;
    // A zero (or NaN) pivot: singular system.
    if (!(std::abs(a[pivot][c]) > 0.0)) return false;
    if (pivot != c) {
      for (int k = 0; k < 4; ++k) std::swap(a[c][k], a[pivot][k]);
      std::swap(b[c], b[pivot]);
    }
    for (int r = c + 1; r < 4; ++r) {
      const double factor = a[r][c] / a[c][c];
      for (int k = c; k < 4; ++k) a[r][k] -= factor * a[c][k];
      b[r] -= factor * b[c];
    }
  }
  for (int c = 3; c >= 0; --c) {
    for (int k = c + 1; k < 4; ++k) b[c] -= a[c][k] * b[k];
    b[c] /= a[c][c];
  }
  return true;
}

bool landmark_gauss_newton_step(const double* coordinate_weight, const double* coordinate_residual, const double* raw,
                                const double* mapped, const RefineMeasure& measure, const LandmarkRows& rows,
                                double (&step)[4]) {
  double normal[4][4] = {};
  for (int p = 0; p < 4; ++p) step[p] = 0.0;
  for (int j = 0; j < 2 * kFitLandmarkCount; ++j) {
    if (coordinate_weight[j] == 0.0) continue;        // no point on this coordinate
    if (raw[j] < 0.0 || raw[j] > 1.0) continue;       // clamped: constant in x, drops out
    // The slope only here, where it is used (a stretched slope costs a division).
    const double slope = measure.slope(raw[j], mapped[j]);
    if (slope == 0.0) continue;                        // below the stretch floor the mapped value is constant
    const auto& r = rows[static_cast<std::size_t>(j)];
    const double curvature = coordinate_weight[j] * slope * slope, pull = coordinate_residual[j] * slope;
    for (int p = 0; p < 4; ++p) {
      step[p] += pull * r[static_cast<std::size_t>(p)];
      for (int q = 0; q < 4; ++q)
        normal[p][q] += curvature * r[static_cast<std::size_t>(p)] * r[static_cast<std::size_t>(q)];
    }
  }
  // A relative ridge: directions the data leave free stay where they are.
  const double ridge = 1e-9 * (normal[0][0] + normal[1][1] + normal[2][2] + normal[3][3]) / 4.0;
  // Nothing unclamped at all: no direction is constrained.
  if (!(ridge > 0.0)) return false;
  for (int p = 0; p < 4; ++p) normal[p][p] += ridge;
  return solve4(normal, step);   // false: singular even with the ridge (non-finite data)
}

ProcrustesCandidate refine_procrustes_candidate(const std::vector<double>& targets, const std::vector<double>& weights,
                                                const RefineMeasure& measure, const LandmarkCoefficients& landmarks,
                                                const ProcrustesCandidate& start, int iterations,
                                                std::vector<std::uint64_t>& seen, std::vector<int>& nearest,
                                                std::vector<int>& next_nearest) {
  const LandmarkRows rows = landmark_rows(landmarks);
  double x[4] = {start.base0.u, start.base0.v, start.base1.u, start.base1.v};
  // `nearest` and `next_nearest` are scratch of weights.size() entries (allocated once per solve).
  double raw[2 * kFitLandmarkCount], mapped[2 * kFitLandmarkCount];
  double error = measured_error(targets, weights, measure, rows, x, nearest, raw, mapped);
  std::uint64_t key = 0;
  for (int j = 0; j < 2 * kFitLandmarkCount; ++j)
    key = key << 2 | (raw[j] < 0.0 ? 1u : raw[j] > 1.0 ? 2u : 0u);   // 16 bits of clamp states
  for (std::size_t i = 0; i < nearest.size(); ++i) {
    // 2 bits per point while they fit in the remaining 48 bits; beyond, a multiplicative hash mixes them in.
    key = nearest.size() <= 24 ? key << 2 | static_cast<std::uint64_t>(nearest[i])
                               : (key ^ static_cast<std::uint64_t>(nearest[i] + 1)) * 0x100000001b3ull;
  }
  if (std::find(seen.begin(), seen.end(), key) != seen.end()) {
    ProcrustesCandidate duplicate = start;
    duplicate.duplicate = true;
    return duplicate;
  }
  seen.push_back(key);
  for (int iteration = 0; iteration < iterations; ++iteration) {
    // Normal equations for the step delta = x_new - x. Every point on landmark coordinate j shares its row r_j and
    // slope s_j, so the per-coordinate sums W_j = sum w_i and R_j = sum w_i residual_i give
    // N = sum_j W_j s_j^2 r_j r_j^T and rhs = sum_j R_j s_j r_j.
    double coordinate_weight[2 * kFitLandmarkCount] = {}, coordinate_residual[2 * kFitLandmarkCount] = {};
    for (std::size_t i = 0; i < weights.size(); ++i) {
      if (!(weights[i] > 0.0)) continue;   // weightless points constrain nothing
      for (int c = 0; c < 2; ++c) {
        const int j = 2 * nearest[i] + c;
        coordinate_weight[j] += weights[i];
        // raw[j] is unclamped wherever the sum is used (clamped coordinates are skipped below).
        coordinate_residual[j] += weights[i] * (targets[static_cast<std::size_t>(c) * weights.size() + i] - mapped[j]);
      }
    }
    double rhs[4];
    if (!landmark_gauss_newton_step(coordinate_weight, coordinate_residual, raw, mapped, measure, rows, rhs)) break;
    double next[4];
    for (int p = 0; p < 4; ++p) next[p] = x[p] + rhs[p];
    double next_raw[2 * kFitLandmarkCount], next_mapped[2 * kFitLandmarkCount];
    const double next_error =
        measured_error(targets, weights, measure, rows, next, next_nearest, next_raw, next_mapped);
    if (!(next_error < error)) break;   // no progress (or NaN): keep the better x
    error = next_error;
    std::copy(next, next + 4, x);
    nearest.swap(next_nearest);
    std::copy(next_raw, next_raw + 2 * kFitLandmarkCount, raw);
    std::copy(next_mapped, next_mapped + 2 * kFitLandmarkCount, mapped);
  }
  // The ranking bound stays the original one (step 3 of the header ranks by it; the refined error is on another
  // measure for the stretched error).
  ProcrustesCandidate refined = start;
  refined.base0 = {x[0], x[1]};
  refined.base1 = {x[2], x[3]};
  return refined;
}


}  // namespace blocklab
