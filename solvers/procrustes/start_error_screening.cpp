// The start-error screening of the `procrustes` solver's search=start_error (solvers/procrustes/
// start_error_screening.h; "Practical HDR Texture Compression" (2008) section 7.1 with the clamp and the stretch of
// section 7.2).
#include "solvers/procrustes/start_error_screening.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace blocklab {

void StartErrorPoints::assign(const std::vector<double>& targets, const std::vector<double>& weights) {
  const std::size_t n = weights.size();
  quads = (n + 3) / 4;
  // Padding: coordinates 0 and weight 0, so a padded point contributes exactly 0.
  u.assign(4 * quads, 0.0f);
  v.assign(4 * quads, 0.0f);
  weight.assign(4 * quads, 0.0f);
  for (std::size_t i = 0; i < n; ++i) {
    u[i] = static_cast<float>(targets[i]);
    v[i] = static_cast<float>(targets[n + i]);
    weight[i] = static_cast<float>(weights[i]);
  }
}

namespace {

// The mapped, clamped landmarks of the candidate's clamped base points in single precision; false for a NaN base
// point (a degenerate fit), which makes every landmark NaN, and the SIMD minimum below would drop NaN distances.
bool start_error_landmarks(const RefineMeasure& measure, const LandmarkRows& rows, const ProcrustesCandidate& candidate,
                           float (&landmark_u)[kFitLandmarkCount], float (&landmark_v)[kFitLandmarkCount]) {
  const double raw_x[4] = {candidate.base0.u, candidate.base0.v, candidate.base1.u, candidate.base1.v};
  for (int p = 0; p < 4; ++p)
    if (std::isnan(raw_x[p])) return false;
  double x[4];
  // Clamped to [0, 1]^4, the box the stored base points live in. Finite from here on.
  for (int p = 0; p < 4; ++p) x[p] = std::min(std::max(raw_x[p], 0.0), 1.0);
  // Landmarks 0 and 1 are the base points themselves (LandmarkCoefficients have along = (0, 1), across = (0, 0) there:
  // rows 0-3 are unit rows), already inside [0, 1]; landmarks 2 and 3 from their rows, then clamped.
  double coordinate[2 * kFitLandmarkCount] = {x[0], x[1], x[2], x[3]};
  for (int j = 4; j < 2 * kFitLandmarkCount; ++j) {
    const auto& r = rows[static_cast<std::size_t>(j)];
    coordinate[j] = std::min(std::max(r[0] * x[0] + r[1] * x[1] + r[2] * x[2] + r[3] * x[3], 0.0), 1.0);
  }
  for (int k = 0; k < kFitLandmarkCount; ++k) {
    // The linear error (no table) uses the coordinates as they are.
    const double u = coordinate[2 * k], v = coordinate[2 * k + 1];
    landmark_u[k] = static_cast<float>(measure.table == nullptr ? u : (*measure.table)(u));
    landmark_v[k] = static_cast<float>(measure.table == nullptr ? v : (*measure.table)(v));
  }
  return true;
}

// The lane sums in a fixed order: the same float on every platform.
float sum_lanes(const float (&lanes)[4]) { return (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]); }

}  // namespace

float candidate_start_error_portable(const StartErrorPoints& points, const RefineMeasure& measure,
                                     const LandmarkRows& rows, const ProcrustesCandidate& candidate) {
  float landmark_u[kFitLandmarkCount], landmark_v[kFitLandmarkCount];
  if (!start_error_landmarks(measure, rows, candidate, landmark_u, landmark_v)) return std::nanf("");
  // The SSE2 kernel's operations lane by lane, in its order (minps(a, b) is a < b ? a : b).
  float lanes[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  for (std::size_t q = 0; q < points.quads; ++q) {
    for (int lane = 0; lane < 4; ++lane) {
      const std::size_t i = 4 * q + static_cast<std::size_t>(lane);
      float nearest = 0.0f;
      for (int k = 0; k < kFitLandmarkCount; ++k) {
        const float du = points.u[i] - landmark_u[k], dv = points.v[i] - landmark_v[k];
        const float d = du * du + dv * dv;
        nearest = k == 0 ? d : (nearest < d ? nearest : d);
      }
      lanes[lane] += nearest * points.weight[i];
    }
  }
  return sum_lanes(lanes);
}

float candidate_start_error(const StartErrorPoints& points, const RefineMeasure& measure, const LandmarkRows& rows,
                            const ProcrustesCandidate& candidate) {
#if defined(__SSE2__)
  float landmark_u[kFitLandmarkCount], landmark_v[kFitLandmarkCount];
  if (!start_error_landmarks(measure, rows, candidate, landmark_u, landmark_v)) return std::nanf("");
  __m128 lu[kFitLandmarkCount], lv[kFitLandmarkCount];
  for (int k = 0; k < kFitLandmarkCount; ++k) {
    lu[k] = _mm_set1_ps(landmark_u[k]);
    lv[k] = _mm_set1_ps(landmark_v[k]);
  }
  // Four points per register: the squared distance to each landmark, its minimum, times the weight.
  __m128 sum = _mm_setzero_ps();
  for (std::size_t q = 0; q < points.quads; ++q) {
    const __m128 u = _mm_loadu_ps(points.u.data() + 4 * q), v = _mm_loadu_ps(points.v.data() + 4 * q);
    __m128 du = _mm_sub_ps(u, lu[0]), dv = _mm_sub_ps(v, lv[0]);
    __m128 nearest = _mm_add_ps(_mm_mul_ps(du, du), _mm_mul_ps(dv, dv));
    for (int k = 1; k < kFitLandmarkCount; ++k) {
      du = _mm_sub_ps(u, lu[k]);
      dv = _mm_sub_ps(v, lv[k]);
      nearest = _mm_min_ps(nearest, _mm_add_ps(_mm_mul_ps(du, du), _mm_mul_ps(dv, dv)));
    }
    sum = _mm_add_ps(sum, _mm_mul_ps(nearest, _mm_loadu_ps(points.weight.data() + 4 * q)));
  }
  float lanes[4];
  _mm_storeu_ps(lanes, sum);
  return sum_lanes(lanes);
#else
  return candidate_start_error_portable(points, measure, rows, candidate);
#endif
}

std::uint64_t start_error_key(float start_error, std::size_t index) {
  std::uint32_t bits;
  std::memcpy(&bits, &start_error, sizeof bits);
  // IEEE order as unsigned integers: negative values (never produced: weights and squares are >= 0, but the key
  // must not depend on it) reversed below the positive ones; NaN of either sign after +inf.
  const std::uint32_t ordered = std::isnan(start_error)   ? 0xffffffffu
                                 : (bits & 0x80000000u) ? ~bits
                                                        : bits | 0x80000000u;
  return static_cast<std::uint64_t>(ordered) << 32 | static_cast<std::uint32_t>(index);
}

std::size_t take_lowest_start_error(std::vector<std::uint64_t>& keys) {
  std::uint64_t lowest = kTakenStartErrorKey;
  for (const std::uint64_t key : keys) lowest = std::min(lowest, key);
  if (lowest == kTakenStartErrorKey) return keys.size();
  const std::size_t index = static_cast<std::uint32_t>(lowest);
  keys[index] = kTakenStartErrorKey;
  return index;
}

void refine_by_start_error(const std::vector<double>& targets, const std::vector<double>& weights,
                           const RefineMeasure& measure, const LandmarkCoefficients& landmarks, int refined,
                           int iterations, std::vector<ProcrustesCandidate>& candidates, StartErrorBuffers& buffers) {
  const LandmarkRows rows = landmark_rows(landmarks);
  StartErrorPoints& packed = buffers.packed;
  packed.assign(targets, weights);
  std::vector<std::uint64_t>& order_keys = buffers.order_keys;
  order_keys.resize(candidates.size());
  for (std::size_t i = 0; i < candidates.size(); ++i)
    order_keys[i] = start_error_key(candidate_start_error(packed, measure, rows, candidates[i]), i);
  std::vector<ProcrustesCandidate>& chosen = buffers.chosen;
  chosen.clear();
  std::vector<std::uint64_t>& seen = buffers.seen;
  seen.clear();
  std::vector<int>& nearest = buffers.nearest;
  std::vector<int>& next_nearest = buffers.next_nearest;
  nearest.resize(weights.size());
  next_nearest.resize(weights.size());
  const bool refine = refined > 0 && iterations > 0;
  const std::size_t wanted = static_cast<std::size_t>(std::max(1, refined));
  while (chosen.size() < wanted) {
    const std::size_t next = take_lowest_start_error(order_keys);
    if (next == candidates.size()) break;   // every candidate taken
    if (!refine) {
      chosen.push_back(candidates[next]);
      continue;
    }
    const ProcrustesCandidate result = refine_procrustes_candidate(targets, weights, measure, landmarks,
                                                                   candidates[next], iterations, seen, nearest,
                                                                   next_nearest);
    // A duplicate takes the same step as an earlier one: it does not count, the next start error is refined.
    if (!result.duplicate) chosen.push_back(result);
  }
  candidates.assign(chosen.begin(), chosen.end());
}

}  // namespace blocklab
