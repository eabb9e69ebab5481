// Partition pre-selection by per-subset PCA line error (see bc7_partition_estimate.h).
//
// For a subset with n texels y_i (lanes scaled by sqrt(weight)), the scatter matrix is S = sum y y^T - s s^T / n
// (s = sum y). The squared distance of the texels to their best line is trace(S) - lambda_max(S); lambda_max is
// approximated from below by a few power iterations (Rayleigh quotient), so the estimate never undercounts.
// All partitions are evaluated together in structure-of-arrays form (partition index innermost).
#include "formats/bc7/bc7_partition_estimate.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "formats/bc7/bc7_tables.h"

namespace blocklab {
namespace bc7 {

namespace {

constexpr int product_count(int lanes) { return lanes * (lanes + 1) / 2; }

// membership[subset_count - 2][subset][texel][partition] = 1 when the texel is in that subset of the partition:
// laid out with the partition innermost so that the moment sums below run over 64 partitions at once
// (structure of arrays, vectorisable).
struct MembershipTable {
  float membership[2][3][16][64];
  MembershipTable() {
    for (int subsets = 2; subsets <= 3; ++subsets)
      for (int subset = 0; subset < 3; ++subset)
        for (int texel = 0; texel < 16; ++texel)
          for (int partition = 0; partition < 64; ++partition)
            membership[subsets - 2][subset][texel][partition] =
                subset < subsets && partition_subsets(subsets, partition)[texel] == subset ? 1.0f : 0.0f;
  }
};

const MembershipTable& membership_table() {
  static const MembershipTable table;   // built on first use (thread-safe static)
  return table;
}

// Line errors (trace(S) - lambda_max(S)) of `n` subsets given their moments in structure-of-arrays form:
// count[p], sum[lane][p], products[k][p] (k over a <= b). Adds each to error[p].
template <int kLanes>
void add_line_errors(int n, const float* count, const float (*sum)[64], const float (*products)[64], float* error) {
  for (int p = 0; p < n; ++p) {
    // Every subset of every partition has at least one texel (tests/unit/test_bc7_tables.cpp), so count >= 1.
    // No comparisons in this loop: with the invariant build's trapping math they would stop vectorisation.
    const float inverse_count = 1.0f / count[p];
    float s[kLanes][kLanes];
    int k = 0;
    #pragma GCC unroll 16
    for (int a = 0; a < kLanes; ++a)
      #pragma GCC unroll 16
      for (int b = a; b < kLanes; ++b, ++k) {
        s[a][b] = products[k][p] - sum[a][p] * sum[b][p] * inverse_count;
        s[b][a] = s[a][b];
      }
    float trace = 0.0f;
    #pragma GCC unroll 16
    for (int a = 0; a < kLanes; ++a) trace += s[a][a];
    // Constant subset: trace 0; the tiny offset keeps 1/trace finite (and changes no ranking).
    const float inverse_trace = 1.0f / (trace + 1e-6f);
    // Power iteration: start from S e with e = (1, 0.618, 0.382, 0.236) (not (1, ..., 1): a principal axis like
    // (1, -1, 0) is orthogonal to that; an axis exactly orthogonal to e does not occur in practice, and a nearly
    // orthogonal one only converges slower, i.e. overestimates the error), then three products with S / trace
    // (trace >= lambda_max keeps |v| <= ~1, so nothing overflows).
    constexpr float kStart[4] = {1.0f, 0.618034f, 0.381966f, 0.236068f};
    float v[kLanes];
    #pragma GCC unroll 16
    for (int a = 0; a < kLanes; ++a) {
      float row = 0.0f;
      #pragma GCC unroll 16
      for (int b = 0; b < kLanes; ++b) row += s[a][b] * kStart[b];
      v[a] = row * inverse_trace;
    }
    #pragma GCC unroll 16
    for (int iteration = 0; iteration < 3; ++iteration) {
      float next[kLanes];
      #pragma GCC unroll 16
      for (int a = 0; a < kLanes; ++a) {
        next[a] = 0.0f;
        #pragma GCC unroll 16
        for (int b = 0; b < kLanes; ++b) next[a] += s[a][b] * v[b];
        next[a] *= inverse_trace;
      }
      #pragma GCC unroll 16
      for (int a = 0; a < kLanes; ++a) v[a] = next[a];
    }
    float v_s_v = 0.0f, v_v = 0.0f;
    #pragma GCC unroll 16
    for (int a = 0; a < kLanes; ++a) {
      float sv = 0.0f;
      #pragma GCC unroll 16
      for (int b = 0; b < kLanes; ++b) sv += s[a][b] * v[b];
      v_s_v += v[a] * sv;
      v_v += v[a] * v[a];
    }
    // v = 0 (start vector orthogonal to the data, or S = 0): v_s_v is 0 too, lambda 0, the whole scatter counts;
    // the offset keeps the division finite without a branch.
    const float lambda = v_s_v / (v_v + 1e-30f);
    // Rounding can make trace - lambda slightly negative (order 1e-7 trace): harmless for a ranking.
    error[p] += trace - lambda;
  }
}

template <int kLanes>
void all_partition_errors(const float (&texels)[16][4], const float weights[4], const int (&lane)[4],
                          int subset_count, int partition_count, float* errors) {
  constexpr int kProducts = product_count(kLanes);
  float y[16][kLanes], products[16][kProducts];
  float total_sum[kLanes] = {}, total_products[kProducts] = {};
  float scale[kLanes], mean[kLanes] = {};
  for (int l = 0; l < kLanes; ++l) scale[l] = std::sqrt(weights[lane[l]]);
  for (int i = 0; i < 16; ++i)
    for (int l = 0; l < kLanes; ++l) mean[l] += texels[i][lane[l]] / 16.0f;
  for (int i = 0; i < 16; ++i) {
    // Centred on the block mean: the scatter is translation invariant, and small moments keep the
    // "total minus other subsets" subtraction accurate in float.
    for (int l = 0; l < kLanes; ++l) {
      y[i][l] = (texels[i][lane[l]] - mean[l]) * scale[l];
      total_sum[l] += y[i][l];
    }
    int k = 0;
    for (int a = 0; a < kLanes; ++a)
      for (int b = a; b < kLanes; ++b, ++k) {
        products[i][k] = y[i][a] * y[i][b];
        total_products[k] += products[i][k];
      }
  }
  for (int p = 0; p < partition_count; ++p) errors[p] = 0.0f;
  const auto& membership = membership_table().membership[subset_count - 2];
  float rest_count[64], rest_sum[kLanes][64], rest_products[kProducts][64];
  for (int p = 0; p < partition_count; ++p) {
    rest_count[p] = 16.0f;
    for (int l = 0; l < kLanes; ++l) rest_sum[l][p] = total_sum[l];
    for (int k = 0; k < kProducts; ++k) rest_products[k][p] = total_products[k];
  }
  for (int subset = 1; subset < subset_count; ++subset) {
    float count[64] = {}, sum[kLanes][64] = {}, product_sum[kProducts][64] = {};
    for (int i = 0; i < 16; ++i) {
      const float* member = membership[subset][i];
      for (int p = 0; p < partition_count; ++p) count[p] += member[p];
      for (int l = 0; l < kLanes; ++l)
        for (int p = 0; p < partition_count; ++p) sum[l][p] += member[p] * y[i][l];
      for (int k = 0; k < kProducts; ++k)
        for (int p = 0; p < partition_count; ++p) product_sum[k][p] += member[p] * products[i][k];
    }
    add_line_errors<kLanes>(partition_count, count, sum, product_sum, errors);
    // Subset 0 is the rest: total minus the other subsets (saves a pass over its texels).
    for (int p = 0; p < partition_count; ++p) rest_count[p] -= count[p];
    for (int l = 0; l < kLanes; ++l)
      for (int p = 0; p < partition_count; ++p) rest_sum[l][p] -= sum[l][p];
    for (int k = 0; k < kProducts; ++k)
      for (int p = 0; p < partition_count; ++p) rest_products[k][p] -= product_sum[k][p];
  }
  add_line_errors<kLanes>(partition_count, rest_count, rest_sum, rest_products, errors);
}

// Errors of partitions [0, partition_count) on the lanes with a positive weight.
void partition_errors(const float (&texels)[16][4], const float weights[4], int subset_count, int partition_count,
                      float* errors) {
  int lane[4] = {0, 0, 0, 0};
  int lane_count = 0;
  for (int l = 0; l < 4; ++l)
    if (weights[l] > 0.0f) lane[lane_count++] = l;
  switch (lane_count) {
    case 1: return all_partition_errors<1>(texels, weights, lane, subset_count, partition_count, errors);
    case 2: return all_partition_errors<2>(texels, weights, lane, subset_count, partition_count, errors);
    case 3: return all_partition_errors<3>(texels, weights, lane, subset_count, partition_count, errors);
    case 4: return all_partition_errors<4>(texels, weights, lane, subset_count, partition_count, errors);
    default:   // no lane counts: every partition is equally good
      for (int partition = 0; partition < partition_count; ++partition) errors[partition] = 0.0f;
  }
}

}  // namespace

float estimate_partition_error(const float (&texels)[16][4], const float weights[4], int subset_count, int partition) {
  float errors[64];
  partition_errors(texels, weights, subset_count, 64, errors);
  return errors[partition];
}

int rank_partitions(const float (&texels)[16][4], const float weights[4], int subset_count, int partition_count,
                    int wanted, int* ranked, float* ranked_errors) {
  float errors[64];
  partition_errors(texels, weights, subset_count, partition_count, errors);
  int order[64];
  std::iota(order, order + partition_count, 0);
  const int kept = std::max(0, std::min(wanted, partition_count));
  // Ties broken by the partition number, so the ranking is a strict total order (deterministic).
  std::partial_sort(order, order + kept, order + partition_count,
                    [&](int a, int b) { return errors[a] < errors[b] || (errors[a] == errors[b] && a < b); });
  std::copy(order, order + kept, ranked);
  if (ranked_errors != nullptr)
    for (int k = 0; k < kept; ++k) ranked_errors[k] = errors[order[k]];
  return kept;
}

}  // namespace bc7
}  // namespace blocklab
