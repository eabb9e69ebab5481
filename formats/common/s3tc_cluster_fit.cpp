// Cluster fit for BC1/BC3 colour endpoints (formats/common/s3tc_color_fit.h, step 3).
//
// Idea (S. Brown, libsquish "ClusterFit"; also Castano, "High Quality DXT Compression using CUDA", 2007): order the
// 16 texels by their projection on the principal axis; an optimal index assignment of a colour line maps that
// order to the palette order monotonically, so it is one of the partitions of the ordered list into consecutive
// runs (4-colour: i texels on code 0 (alpha = 1), j on code 2 (alpha = 2/3), k on code 3 (alpha = 1/3), the rest on
// code 1 (alpha = 0); 3-colour: i on code 0, j on the midpoint (alpha = 1/2), the rest on code 1). There are
// C(19, 3) = 969 4-colour and C(18, 2) = 153 3-colour partitions.
//
// For each partition the least-squares endpoints A, B solve per channel
//     [sum alpha^2   sum alpha beta] [A]   [sum alpha x]
//     [sum alpha beta sum beta^2   ] [B] = [sum beta x ]       (beta = 1 - alpha)
// where the alpha sums depend only on (i, j, k) and the x sums come from prefix sums S of the ordered texels:
// sum alpha x = (S_i + S_{i+j} + S_{i+j+k}) / 3 (4-colour) or (S_i + S_{i+j}) / 2 (3-colour), sum beta x = S_16 -
// sum alpha x. A and B are then quantised to the RGB565 lattice and the partition is scored by the exact
// closed-form squared error of the QUANTISED endpoints for that assignment,
//     E_c = A^2 sum alpha^2 + B^2 sum beta^2 + 2 A B sum alpha beta - 2 A sum alpha x - 2 B sum beta x (+ sum x^2),
// weighted by channel (the constant sum x^2 is dropped). Scoring the quantised endpoints (not the continuous
// optimum) is what makes the fit quantisation-aware. Quantisation here is round(A * max / 255) followed by bit
// replication (the nearest lattice value up to a fraction of a step); the polish that follows works on the exact
// lattice.
//
// Vectorisation: the partitions' constants are tables in enumeration order, and alpha_x of every partition is
// computed first (for fixed (i, j) the partitions differ only in k, and S_{i+j+k} is contiguous in k), so a SIMD
// step scores consecutive partitions with plain loads. The kernel (s3tc_cluster_fit_kernel.inc) is compiled for
// SSE2 (4 lanes; a plain 4-element loop off x86) and, when the CPU has it (__builtin_cpu_supports, checked once),
// for AVX2 (8 lanes). Every path performs the
// same IEEE operations per lane in the same order (the build has -ffp-contract=off and the AVX2 region does not
// enable FMA), so all give the same bits; tests/unit/test_s3tc_cluster_fit.cpp compares them with each other and
// with a scalar transcription of the definition above.
//
// Ties: the answer is the FIRST partition in the enumeration order (i, j, k ascending) with the smallest score.
// The search below scores partitions out of order, so a partition replaces the best one when its score is smaller,
// or equal with an earlier position; that selects the same partition in any visiting order.
//
// Exact pruning (the answer is unchanged, only the work shrinks). Fix a partition and a channel; write M for its
// exact normal matrix (aa, ab; ab, bb) (rationals with aa + bb + 2 ab = 16, sum alpha = aa + ab, det = 16 aa -
// (sum alpha)^2 = sum over texel pairs of (alpha_p - alpha_q)^2, so det = 0 (all texels on one code: the singular
// partitions, removed anyway) or det >= 5/3 (4-colour; 15/4 for 3-colour)), and c = (ax, T - ax) with ax =
// (S_i + S_{i+j} + S_{i+j+k}) / 3 taken exactly from the float prefix sums. For every real point z = (A, B),
//     Q(z) = z^T M z - 2 c^T z  >=  min Q = -c^T M^-1 c = -T^2 / 16 - (16 ax - T sum alpha)^2 / (16 det)
// (the second form is algebra using aa + bb + 2 ab = 16). With the centred prefix sums C_n = S_n - n T / 16 the
// last term is h v^2 with v = C_i + C_{i+j} + C_{i+j+k} and h = 16 / (9 det) (3-colour: v = C_i + C_{i+j},
// h = 4 / det). The quantised endpoints are one such point, so a partition's weighted score is at least
//     -K - D,   K = sum_c w_c T_c^2 / 16 (one per block),   D = h sum_c w_c v_c^2 (a few operations per lane).
// A step whose D are all below t = -best - K - margin cannot change the answer: each of its scores is > best, and
// replacing needs a score <= best. The margin covers the float rounding of both sides. Bounds, per
// channel and unit weight, with u = 2^-24, texels in [0, R] (R <= 255, so |S_n|, |ax| <= 16 R, |C_n| <= 4 R)
// and quantised endpoints in [0, Z], Z = 255 (first-order terms; each bound is then doubled):
//   * the score uses float coefficients: aa, bb each off by <= 3u * 16, ab by <= 2u * 32/9 (3-colour: exact), ax
//     by <= 59 u R and T - ax by <= 75 u R, moving Q(z) by <= 111 u Z^2 + 267 u Z R;
//   * evaluating Q at z in float (nine operations on terms <= 16 Z, 16 R): <= u Z (164 Z + 224 R); weighting and
//     summing three channels: <= 3 u |Q| <= u Z (118 Z + 192 R);
//   * D: C_n rounded once (from double), v within 32 u R, and h v^2 <= sum (x - mean)^2 <= 4 R^2 (the exact
//     minimum is >= -sum x^2), so D is off by <= 152 u R^2 summed over the weights; K (rounded from double) and
//     the two subtractions in t add <= 48 u R^2.
// Total per unit weight <= u (391 Z^2 + 683 Z R + 200 R^2) <= 4.94 at R = 255; the margin is twice the bound,
// with R the channel's largest texel. Blocks with a texel outside [0, 255] or a weight that is negative, not
// finite or above 1e12 are not pruned. Padding lanes and singular partitions get D = -inf (never keep a step).
//
// Order: pass 1 computes every partition's D; the step holding the largest D (the smallest bound, usually close
// to the best partition) is scored first as the seed, so t is nearly final from the start; pass 2 then scores, in
// order, the steps that the best so far does not prune (t re-read every 32 steps). Blocks of small spread (little
// more than the 565 rounding error) skip the bound: it would prune too little to pay for pass 1. Measured effect:
// formats/bc1/README.md.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include "core/cpu_features.h"
#if BLOCKLAB_HAS_AVX2_PATHS
#include <immintrin.h>
#define BLOCKLAB_CLUSTER_FIT_AVX2 1
#endif

#include "formats/common/s3tc_color_fit.h"

namespace blocklab {

namespace {

#if defined(__SSE2__)
// Four float lanes (SSE2). Rounding of to_int is the MXCSR default, round to nearest even.
struct Lanes4 {
  static constexpr int kWidth = 4;
  __m128 v;
  static Lanes4 all(float x) { return {_mm_set1_ps(x)}; }
  static Lanes4 load(const float* p) { return {_mm_loadu_ps(p)}; }
  static Lanes4 ramp(float base) { return {_mm_setr_ps(base, base + 1.0f, base + 2.0f, base + 3.0f)}; }
  void store(float* p) const { _mm_storeu_ps(p, v); }
  static Lanes4 lane_numbers() { return ramp(0.0f); }
};
inline Lanes4 operator+(Lanes4 a, Lanes4 b) { return {_mm_add_ps(a.v, b.v)}; }
inline Lanes4 operator-(Lanes4 a, Lanes4 b) { return {_mm_sub_ps(a.v, b.v)}; }
inline Lanes4 operator*(Lanes4 a, Lanes4 b) { return {_mm_mul_ps(a.v, b.v)}; }
inline Lanes4 operator/(Lanes4 a, Lanes4 b) { return {_mm_div_ps(a.v, b.v)}; }
inline Lanes4 clamp_0_255(Lanes4 a) { return {_mm_min_ps(_mm_max_ps(a.v, _mm_setzero_ps()), _mm_set1_ps(255.0f))}; }
// mask ? a : b, with mask from compare_* (all-ones lanes).
inline Lanes4 blend(Lanes4 mask, Lanes4 a, Lanes4 b) {
  return {_mm_or_ps(_mm_and_ps(mask.v, a.v), _mm_andnot_ps(mask.v, b.v))};
}
inline Lanes4 less_equal_mask(Lanes4 a, Lanes4 b) { return {_mm_cmple_ps(a.v, b.v)}; }
inline Lanes4 greater_mask(Lanes4 a, Lanes4 b) { return {_mm_cmpgt_ps(a.v, b.v)}; }
inline Lanes4 and_mask(Lanes4 a, Lanes4 b) { return {_mm_and_ps(a.v, b.v)}; }
inline bool any_less_equal(Lanes4 a, float bound) {
  return _mm_movemask_ps(_mm_cmple_ps(a.v, _mm_set1_ps(bound))) != 0;
}
inline bool all_less(Lanes4 a, float bound) { return _mm_movemask_ps(_mm_cmplt_ps(a.v, _mm_set1_ps(bound))) == 0xF; }
// round(a * scale) then bit replication (shift_left, shift_right) back to 8 bits; also returns the lattice values.
inline Lanes4 quantize_expand(Lanes4 a, float scale, int shift_left, int shift_right, int lattice[4]) {
  const __m128i q = _mm_cvtps_epi32(_mm_mul_ps(a.v, _mm_set1_ps(scale)));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(lattice), q);
  const __m128i expanded = _mm_or_si128(_mm_sll_epi32(q, _mm_cvtsi32_si128(shift_left)),
                                        _mm_srl_epi32(q, _mm_cvtsi32_si128(shift_right)));
  return {_mm_cvtepi32_ps(expanded)};
}
#else
struct Lanes4 {
  static constexpr int kWidth = 4;
  float v[4];
  static Lanes4 all(float x) { return {{x, x, x, x}}; }
  static Lanes4 load(const float* p) { return {{p[0], p[1], p[2], p[3]}}; }
  static Lanes4 ramp(float base) { return {{base, base + 1.0f, base + 2.0f, base + 3.0f}}; }
  void store(float* p) const { std::memcpy(p, v, sizeof v); }
  static Lanes4 lane_numbers() { return ramp(0.0f); }
};
#define BLOCKLAB_LANEWISE(expr) \
  Lanes4 r;                     \
  for (int l = 0; l < 4; ++l) r.v[l] = (expr); \
  return r
inline Lanes4 operator+(Lanes4 a, Lanes4 b) { BLOCKLAB_LANEWISE(a.v[l] + b.v[l]); }
inline Lanes4 operator-(Lanes4 a, Lanes4 b) { BLOCKLAB_LANEWISE(a.v[l] - b.v[l]); }
inline Lanes4 operator*(Lanes4 a, Lanes4 b) { BLOCKLAB_LANEWISE(a.v[l] * b.v[l]); }
inline Lanes4 operator/(Lanes4 a, Lanes4 b) { BLOCKLAB_LANEWISE(a.v[l] / b.v[l]); }
// Same NaN behaviour as SSE max(a, 0) then min(., 255): NaN -> 0 (maxps returns the second operand on NaN).
inline Lanes4 clamp_0_255(Lanes4 a) {
  BLOCKLAB_LANEWISE(std::fmin(a.v[l] > 0.0f ? a.v[l] : 0.0f, 255.0f));
}
inline float bits_mask(bool condition) {
  const std::uint32_t bits = condition ? 0xFFFFFFFFu : 0u;
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}
inline bool mask_set(float f) {
  std::uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  return bits != 0;
}
inline Lanes4 blend(Lanes4 mask, Lanes4 a, Lanes4 b) { BLOCKLAB_LANEWISE(mask_set(mask.v[l]) ? a.v[l] : b.v[l]); }
inline Lanes4 less_equal_mask(Lanes4 a, Lanes4 b) { BLOCKLAB_LANEWISE(bits_mask(a.v[l] <= b.v[l])); }
inline Lanes4 greater_mask(Lanes4 a, Lanes4 b) { BLOCKLAB_LANEWISE(bits_mask(a.v[l] > b.v[l])); }
inline Lanes4 and_mask(Lanes4 a, Lanes4 b) { BLOCKLAB_LANEWISE(bits_mask(mask_set(a.v[l]) && mask_set(b.v[l]))); }
inline bool any_less_equal(Lanes4 a, float bound) {
  for (float x : a.v)
    if (x <= bound) return true;
  return false;
}
inline bool all_less(Lanes4 a, float bound) {
  for (float x : a.v)
    if (!(x < bound)) return false;
  return true;
}
inline Lanes4 quantize_expand(Lanes4 a, float scale, int shift_left, int shift_right, int lattice[4]) {
  Lanes4 r;
  for (int l = 0; l < 4; ++l) {
    lattice[l] = static_cast<int>(std::nearbyint(a.v[l] * scale));   // round to nearest even, like cvtps2dq
    r.v[l] = static_cast<float>((lattice[l] << shift_left) | (lattice[l] >> shift_right));
  }
  return r;
}
#undef BLOCKLAB_LANEWISE
#endif

// Channel c: lattice scale (max / 255) and the bit-replication shifts (5 bits: <<3 | >>2, 6 bits: <<2 | >>4).
constexpr float kLatticeScale[3] = {31.0f / 255.0f, 63.0f / 255.0f, 31.0f / 255.0f};
constexpr int kShiftLeft[3] = {3, 2, 3};
constexpr int kShiftRight[3] = {2, 4, 2};

struct BestPartition {
  float error = std::numeric_limits<float>::infinity();
  int index = -1;   // position in the enumeration; -1: none yet
  int lattice_a[3] = {0, 0, 0}, lattice_b[3] = {0, 0, 0};
  template <int width>
  void keep(float new_error, int new_index, const int (&a)[3][width], const int (&b)[3][width], int lane) {
    error = new_error;
    index = new_index;
    for (int channel = 0; channel < 3; ++channel) {
      lattice_a[channel] = a[channel][lane];
      lattice_b[channel] = b[channel][lane];
    }
  }
};

constexpr float kSingularDeterminant = 1e-3f;   // all texels on one code (see the file comment)

// The exact determinant 16 sum alpha^2 - (sum alpha)^2 of a partition with run lengths i, j, k (3-colour: i, j;
// k = 0), in double: small integers over 81 (or 16), exact.
double exact_determinant(Bc1Mode mode, int i, int j, int k) {
  const bool four = mode == Bc1Mode::four_color;
  const double sum_alpha_sq = four ? i + (4.0 * j + k) / 9.0 : i + j / 4.0;
  const double sum_alpha = four ? i + (2.0 * j + k) / 3.0 : i + j / 2.0;
  return 16.0 * sum_alpha_sq - sum_alpha * sum_alpha;
}

constexpr int kMaxPartitions = 969;               // C(19, 3) 4-colour partitions
constexpr int kAlphaRow = kMaxPartitions + 16;    // per-partition arrays, with room for the widest step past the end

// The partitions sharing i and j (4-colour) or i (3-colour): `count` consecutive positions from `first`, the last
// run of the one at first + k ending at second_run_end + k.
struct PartitionRun {
  int first_run_end, second_run_end, first, count;
};

// The block-independent constants of every partition in enumeration order (4-colour: i, j, k ascending; 3-colour:
// i, j): the normal-equation matrix, its inverse determinant, a penalty that is 0 for real partitions and +inf for
// singular ones (all texels on one code: they divide by 1 instead of ~0 and score +inf) and for the padding past
// the end, and the factor h of the pruning bound (0 where there is no partition).
struct PartitionTable {
  int count = 0;
  std::vector<float> aa, bb, ab, inverse, penalty, bound_scale;   // kAlphaRow entries
  std::vector<PartitionRun> runs;
};

// Appends one partition; aa, bb, ab in the float operations of the definition (the file comment).
void add_partition(PartitionTable& table, Bc1Mode mode, int i, int j, int k, float aa, float bb, float ab) {
  const float determinant = aa * bb - ab * ab;
  const bool valid = determinant > kSingularDeterminant;
  table.aa.push_back(aa);
  table.bb.push_back(bb);
  table.ab.push_back(ab);
  table.inverse.push_back(1.0f / (valid ? determinant : 1.0f));
  table.penalty.push_back(valid ? 0.0f : std::numeric_limits<float>::infinity());
  const double h = (mode == Bc1Mode::four_color ? 16.0 / 9.0 : 4.0) / exact_determinant(mode, i, j, k);
  table.bound_scale.push_back(valid ? static_cast<float>(h) : 0.0f);
  ++table.count;
}

PartitionTable build_partition_table(Bc1Mode mode) {
  PartitionTable table;
  const float ninth = 1.0f / 9.0f;
  if (mode == Bc1Mode::four_color) {
    for (int i = 0; i <= 16; ++i)
      for (int j = 0; i + j <= 16; ++j) {
        table.runs.push_back({i, i + j, table.count, 17 - i - j});
        for (int k = 0; i + j + k <= 16; ++k) {
          const float fi = static_cast<float>(i), fj = static_cast<float>(j), fk = static_cast<float>(k);
          const float l = static_cast<float>(16 - i - j) - fk;
          add_partition(table, mode, i, j, k, fi + (4.0f * fj + fk) * ninth, l + (fj + 4.0f * fk) * ninth,
                        2.0f * (fj + fk) * ninth);
        }
      }
  } else {
    for (int i = 0; i <= 16; ++i) {
      table.runs.push_back({i, i, table.count, 17 - i});
      for (int j = 0; i + j <= 16; ++j) {
        const float fi = static_cast<float>(i), fj = static_cast<float>(j);
        const float l = static_cast<float>(16 - i) - fj;
        add_partition(table, mode, i, j, 0, fi + fj * 0.25f, l + fj * 0.25f, fj * 0.25f);
      }
    }
  }
  const auto pad = [](std::vector<float>& values, float value) { values.resize(kAlphaRow, value); };
  pad(table.aa, 0.0f);
  pad(table.bb, 0.0f);
  pad(table.ab, 0.0f);
  pad(table.inverse, 1.0f);
  pad(table.penalty, std::numeric_limits<float>::infinity());
  pad(table.bound_scale, 0.0f);
  return table;
}

const PartitionTable& partition_table(Bc1Mode mode) {
  static const PartitionTable four = build_partition_table(Bc1Mode::four_color);   // thread-safe statics
  static const PartitionTable three = build_partition_table(Bc1Mode::three_color);
  return mode == Bc1Mode::four_color ? four : three;
}

// The block's side of the pruning bound (file comment): centred prefix sums C_n = S_n - n T / 16 per channel
// (padded to 24 with C_16 = 0 for the 8-lane loads of pass 1), K = sum_c w_c T_c^2 / 16 and the margin; `enabled`
// is false where the rounding analysis does not apply or the block's spread is too small for the bound to pay.
struct PruningBound {
  bool enabled = false;
  float centred[3][24];
  float flat_score = 0.0f;   // K
  float margin = 0.0f;
};

constexpr double kMaxPrunedWeight = 1e12;
// Blocks whose weighted spread sum_c w_c sum (x - mean)^2 is below this times sum_c w_c are scored without the
// bound: their scores are dominated by the 565 rounding, which the bound does not see, so it prunes little
// (tuned on the wang residual blocks of GoldenGate.exr, bc1 on kodim01 and ldr-rgb-diffuse.png).
constexpr double kMinPrunedSpread = 300.0;

PruningBound pruning_bound(const ColorBlock& block, const float prefix[3][24]) {
  PruningBound bound;
  constexpr double u = 1.0 / 16777216.0, z = 255.0;   // unit roundoff 2^-24, largest quantised endpoint
  double flat = 0.0, margin = 0.0, spread = 0.0, weight_sum = 0.0;
  for (int channel = 0; channel < 3; ++channel) {
    const double w = block.weights[channel];
    if (!(w >= 0.0 && w <= kMaxPrunedWeight)) return bound;
    float largest = 0.0f;
    for (int texel = 0; texel < 16; ++texel) {
      const float x = block.texels[texel][channel];
      if (!(x >= 0.0f && x <= 255.0f)) return bound;
      largest = std::max(largest, x);
    }
    const double r = largest, total = prefix[channel][16];
    for (int n = 0; n < 24; ++n)
      bound.centred[channel][n] = static_cast<float>(prefix[channel][n] - std::min(n, 16) * total / 16.0);
    flat += w * total * total / 16.0;
    double squares = 0.0;
    for (int texel = 0; texel < 16; ++texel)
      squares += static_cast<double>(block.texels[texel][channel]) * block.texels[texel][channel];
    spread += w * (squares - total * total / 16.0);
    weight_sum += w;
    margin += 2.0 * w * u * (391.0 * z * z + 683.0 * z * r + 200.0 * r * r);
  }
  if (spread < kMinPrunedSpread * weight_sum) return bound;   // pass 1 would cost more than it saves
  bound.enabled = true;
  bound.flat_score = static_cast<float>(flat);
  bound.margin = static_cast<float>(margin);
  return bound;
}

// Steps whose every lane has D below this are pruned (file comment).
inline float pruning_threshold(const PruningBound& bound, const BestPartition& best) {
  return -best.error - bound.flat_score - bound.margin;
}

namespace portable {
using Lanes = Lanes4;
#include "formats/common/s3tc_cluster_fit_kernel.inc"
}  // namespace portable

#if BLOCKLAB_CLUSTER_FIT_AVX2
#pragma GCC push_options
#pragma GCC target("avx2")
// Eight float lanes (AVX2): the same operations as Lanes4 lane by lane.
struct Lanes8 {
  static constexpr int kWidth = 8;
  __m256 v;
  static Lanes8 all(float x) { return {_mm256_set1_ps(x)}; }
  static Lanes8 load(const float* p) { return {_mm256_loadu_ps(p)}; }
  static Lanes8 lane_numbers() { return {_mm256_setr_ps(0, 1, 2, 3, 4, 5, 6, 7)}; }
  void store(float* p) const { _mm256_storeu_ps(p, v); }
};
inline Lanes8 operator+(Lanes8 a, Lanes8 b) { return {_mm256_add_ps(a.v, b.v)}; }
inline Lanes8 operator-(Lanes8 a, Lanes8 b) { return {_mm256_sub_ps(a.v, b.v)}; }
inline Lanes8 operator*(Lanes8 a, Lanes8 b) { return {_mm256_mul_ps(a.v, b.v)}; }
inline Lanes8 clamp_0_255(Lanes8 a) {
  return {_mm256_min_ps(_mm256_max_ps(a.v, _mm256_setzero_ps()), _mm256_set1_ps(255.0f))};
}
inline Lanes8 blend(Lanes8 mask, Lanes8 a, Lanes8 b) { return {_mm256_blendv_ps(b.v, a.v, mask.v)}; }
inline Lanes8 greater_mask(Lanes8 a, Lanes8 b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_GT_OQ)}; }
inline bool all_less(Lanes8 a, float bound) {
  return _mm256_movemask_ps(_mm256_cmp_ps(a.v, _mm256_set1_ps(bound), _CMP_LT_OQ)) == 0xFF;
}
inline bool any_less_equal(Lanes8 a, float bound) {
  return _mm256_movemask_ps(_mm256_cmp_ps(a.v, _mm256_set1_ps(bound), _CMP_LE_OQ)) != 0;
}
inline Lanes8 quantize_expand(Lanes8 a, float scale, int shift_left, int shift_right, int lattice[8]) {
  const __m256i q = _mm256_cvtps_epi32(_mm256_mul_ps(a.v, _mm256_set1_ps(scale)));
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(lattice), q);
  const __m256i expanded = _mm256_or_si256(_mm256_sll_epi32(q, _mm_cvtsi32_si128(shift_left)),
                                           _mm256_srl_epi32(q, _mm_cvtsi32_si128(shift_right)));
  return {_mm256_cvtepi32_ps(expanded)};
}

namespace avx2 {
using Lanes = Lanes8;
#include "formats/common/s3tc_cluster_fit_kernel.inc"
}  // namespace avx2
#pragma GCC pop_options
#endif

}  // namespace

bool cluster_fit_avx2_available() { return cpu_has_avx2(); }

ColorCandidate cluster_fit(const ColorBlock& block, const std::array<float, 3>& axis, Bc1Mode mode) {
  return cluster_fit(block, axis, mode, ClusterFitPath::automatic);
}

ColorCandidate cluster_fit(const ColorBlock& block, const std::array<float, 3>& axis, Bc1Mode mode,
                           ClusterFitPath path) {
  // Order along the axis: insertion sort of 16 keys, stable (equal projections keep texel order), deterministic.
  int order[16];
  float key[16];
  for (int texel = 0; texel < 16; ++texel) {
    const float projection = axis[0] * block.texels[texel][0] + axis[1] * block.texels[texel][1] +
                             axis[2] * block.texels[texel][2];
    int position = texel;
    while (position > 0 && key[position - 1] > projection) {
      key[position] = key[position - 1];
      order[position] = order[position - 1];
      --position;
    }
    key[position] = projection;
    order[position] = texel;
  }
  // Prefix sums per channel, padded to 24 with the total so that 8-lane loads past index 16 stay in bounds.
  float prefix[3][24];
  for (int channel = 0; channel < 3; ++channel) {
    prefix[channel][0] = 0.0f;
    for (int n = 0; n < 16; ++n) prefix[channel][n + 1] = prefix[channel][n] + block.texels[order[n]][channel];
    for (int n = 17; n < 24; ++n) prefix[channel][n] = prefix[channel][16];
  }
  const PruningBound bound = path == ClusterFitPath::unpruned ? PruningBound{} : pruning_bound(block, prefix);
  const PartitionTable& table = partition_table(mode);
  const bool four = mode == Bc1Mode::four_color;
  BestPartition best;
  const bool wide = path == ClusterFitPath::avx2 || (path == ClusterFitPath::automatic && cpu_has_avx2());
#if BLOCKLAB_CLUSTER_FIT_AVX2
  if (wide && cpu_has_avx2()) {
    if (four)
      avx2::search_partitions<true>(block, prefix, bound, table, best);
    else
      avx2::search_partitions<false>(block, prefix, bound, table, best);
  } else
#endif
  {
    static_cast<void>(wide);
    if (four)
      portable::search_partitions<true>(block, prefix, bound, table, best);
    else
      portable::search_partitions<false>(block, prefix, bound, table, best);
  }
  ColorCandidate candidate;
  candidate.mode = mode;
  for (int channel = 0; channel < 3; ++channel) {
    candidate.endpoints[0][channel] = best.lattice_a[channel];
    candidate.endpoints[1][channel] = best.lattice_b[channel];
  }
  return candidate;
}

}  // namespace blocklab
