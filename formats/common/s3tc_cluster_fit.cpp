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
// Speed: for fixed (i, j) the partitions differ only in k, and S_{i+j+k} is contiguous in k, so four values of k
// are scored at once with 4-lane SIMD (SSE2 on x86-64; a plain 4-element loop with the same operations in the
// same order elsewhere, so both paths give the same bits). The 3-colour partitions vectorise over j likewise.
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "formats/common/s3tc_color_fit.h"

namespace blocklab {

namespace {

#if defined(__SSE2__)
// Four float lanes (SSE2). Rounding of to_int is the MXCSR default, round to nearest even.
struct Lanes {
  __m128 v;
  static Lanes all(float x) { return {_mm_set1_ps(x)}; }
  static Lanes load(const float* p) { return {_mm_loadu_ps(p)}; }
  static Lanes ramp(float base) { return {_mm_setr_ps(base, base + 1.0f, base + 2.0f, base + 3.0f)}; }
  void store(float* p) const { _mm_storeu_ps(p, v); }
};
inline Lanes operator+(Lanes a, Lanes b) { return {_mm_add_ps(a.v, b.v)}; }
inline Lanes operator-(Lanes a, Lanes b) { return {_mm_sub_ps(a.v, b.v)}; }
inline Lanes operator*(Lanes a, Lanes b) { return {_mm_mul_ps(a.v, b.v)}; }
inline Lanes operator/(Lanes a, Lanes b) { return {_mm_div_ps(a.v, b.v)}; }
inline Lanes clamp_0_255(Lanes a) { return {_mm_min_ps(_mm_max_ps(a.v, _mm_setzero_ps()), _mm_set1_ps(255.0f))}; }
// mask ? a : b, with mask from compare_* (all-ones lanes).
inline Lanes blend(Lanes mask, Lanes a, Lanes b) {
  return {_mm_or_ps(_mm_and_ps(mask.v, a.v), _mm_andnot_ps(mask.v, b.v))};
}
inline Lanes less_equal_mask(Lanes a, Lanes b) { return {_mm_cmple_ps(a.v, b.v)}; }
inline Lanes greater_mask(Lanes a, Lanes b) { return {_mm_cmpgt_ps(a.v, b.v)}; }
inline Lanes and_mask(Lanes a, Lanes b) { return {_mm_and_ps(a.v, b.v)}; }
inline bool any_less(Lanes a, float bound) { return _mm_movemask_ps(_mm_cmplt_ps(a.v, _mm_set1_ps(bound))) != 0; }
// round(a * scale) then bit replication (shift_left, shift_right) back to 8 bits; also returns the lattice values.
inline Lanes quantize_expand(Lanes a, float scale, int shift_left, int shift_right, int lattice[4]) {
  const __m128i q = _mm_cvtps_epi32(_mm_mul_ps(a.v, _mm_set1_ps(scale)));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(lattice), q);
  const __m128i expanded = _mm_or_si128(_mm_sll_epi32(q, _mm_cvtsi32_si128(shift_left)),
                                        _mm_srl_epi32(q, _mm_cvtsi32_si128(shift_right)));
  return {_mm_cvtepi32_ps(expanded)};
}
#else
struct Lanes {
  float v[4];
  static Lanes all(float x) { return {{x, x, x, x}}; }
  static Lanes load(const float* p) { return {{p[0], p[1], p[2], p[3]}}; }
  static Lanes ramp(float base) { return {{base, base + 1.0f, base + 2.0f, base + 3.0f}}; }
  void store(float* p) const { std::memcpy(p, v, sizeof v); }
};
#define BLOCKLAB_LANEWISE(expr) \
  Lanes r;                      \
  for (int l = 0; l < 4; ++l) r.v[l] = (expr); \
  return r
inline Lanes operator+(Lanes a, Lanes b) { BLOCKLAB_LANEWISE(a.v[l] + b.v[l]); }
inline Lanes operator-(Lanes a, Lanes b) { BLOCKLAB_LANEWISE(a.v[l] - b.v[l]); }
inline Lanes operator*(Lanes a, Lanes b) { BLOCKLAB_LANEWISE(a.v[l] * b.v[l]); }
inline Lanes operator/(Lanes a, Lanes b) { BLOCKLAB_LANEWISE(a.v[l] / b.v[l]); }
// Same NaN behaviour as SSE max(a, 0) then min(., 255): NaN -> 0 (maxps returns the second operand on NaN).
inline Lanes clamp_0_255(Lanes a) {
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
inline Lanes blend(Lanes mask, Lanes a, Lanes b) { BLOCKLAB_LANEWISE(mask_set(mask.v[l]) ? a.v[l] : b.v[l]); }
inline Lanes less_equal_mask(Lanes a, Lanes b) { BLOCKLAB_LANEWISE(bits_mask(a.v[l] <= b.v[l])); }
inline Lanes greater_mask(Lanes a, Lanes b) { BLOCKLAB_LANEWISE(bits_mask(a.v[l] > b.v[l])); }
inline Lanes and_mask(Lanes a, Lanes b) { BLOCKLAB_LANEWISE(bits_mask(mask_set(a.v[l]) && mask_set(b.v[l]))); }
inline bool any_less(Lanes a, float bound) {
  for (float x : a.v)
    if (x < bound) return true;
  return false;
}
inline Lanes quantize_expand(Lanes a, float scale, int shift_left, int shift_right, int lattice[4]) {
  Lanes r;
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
  int lattice_a[3] = {0, 0, 0}, lattice_b[3] = {0, 0, 0};
};

// The block-independent constants of four partitions (one SIMD step), precomputed once per mode in loop order:
// the normal-equation matrix, its inverse determinant and a penalty that is 0 for real partitions and +inf for
// padding lanes and singular partitions (those lanes divide by 1 instead of ~0 and their score becomes +inf).
struct PartitionQuad {
  alignas(16) float aa[4];
  alignas(16) float bb[4];
  alignas(16) float ab[4];
  alignas(16) float inverse[4];
  alignas(16) float penalty[4];
};

// Scores four partitions given their constants (`quad`) and alpha_x per channel. Lanes are examined in order, so
// the first best partition wins ties.
inline void score_lanes(const ColorBlock& block, const PartitionQuad& quad, const Lanes alpha_x[3], const float* totals,
                        BestPartition& best) {
  const Lanes aa = Lanes::load(quad.aa), bb = Lanes::load(quad.bb), ab = Lanes::load(quad.ab),
              inverse = Lanes::load(quad.inverse);
  Lanes error = Lanes::all(0.0f);
  int lattice_a[3][4], lattice_b[3][4];
  for (int channel = 0; channel < 3; ++channel) {
    const Lanes beta_x = Lanes::all(totals[channel]) - alpha_x[channel];
    const Lanes a = (bb * alpha_x[channel] - ab * beta_x) * inverse;
    const Lanes b = (aa * beta_x - ab * alpha_x[channel]) * inverse;
    const Lanes qa = quantize_expand(clamp_0_255(a), kLatticeScale[channel], kShiftLeft[channel],
                                     kShiftRight[channel], lattice_a[channel]);
    const Lanes qb = quantize_expand(clamp_0_255(b), kLatticeScale[channel], kShiftLeft[channel],
                                     kShiftRight[channel], lattice_b[channel]);
    const Lanes two = Lanes::all(2.0f);
    error = error + Lanes::all(block.weights[channel]) *
                        (qa * (qa * aa + two * (qb * ab - alpha_x[channel])) + qb * (qb * bb - two * beta_x));
  }
  error = error + Lanes::load(quad.penalty);   // +0 keeps real scores, +inf removes the other lanes
  if (!any_less(error, best.error)) return;   // the common case: nothing better in these four
  float errors[4];
  error.store(errors);
  for (int lane = 0; lane < 4; ++lane)
    if (errors[lane] < best.error) {
      best.error = errors[lane];
      for (int channel = 0; channel < 3; ++channel) {
        best.lattice_a[channel] = lattice_a[channel][lane];
        best.lattice_b[channel] = lattice_b[channel][lane];
      }
    }
}

constexpr float kSingularDeterminant = 1e-3f;   // all texels on one code (see the file comment)

void push_quad(std::vector<PartitionQuad>& quads, Lanes valid, Lanes aa, Lanes bb, Lanes ab) {
  PartitionQuad quad;
  aa.store(quad.aa);
  bb.store(quad.bb);
  ab.store(quad.ab);
  const Lanes determinant = blend(valid, aa * bb - ab * ab, Lanes::all(1.0f));
  (Lanes::all(1.0f) / determinant).store(quad.inverse);
  blend(valid, Lanes::all(0.0f), Lanes::all(std::numeric_limits<float>::infinity())).store(quad.penalty);
  quads.push_back(quad);
}

// The quads in the exact order cluster_fit visits them (4-colour: i, j, then k in steps of 4; 3-colour: i, then j
// in steps of 4).
std::vector<PartitionQuad> build_quads(Bc1Mode mode) {
  std::vector<PartitionQuad> quads;
  const Lanes ninth = Lanes::all(1.0f / 9.0f), quarter = Lanes::all(0.25f), singular = Lanes::all(kSingularDeterminant);
  if (mode == Bc1Mode::four_color) {
    for (int i = 0; i <= 16; ++i)
      for (int j = 0; i + j <= 16; ++j) {
        const int k_max = 16 - i - j;
        for (int k0 = 0; k0 <= k_max; k0 += 4) {
          const Lanes k = Lanes::ramp(static_cast<float>(k0));
          const Lanes fi = Lanes::all(static_cast<float>(i)), fj = Lanes::all(static_cast<float>(j));
          const Lanes l = Lanes::all(static_cast<float>(16 - i - j)) - k;
          const Lanes aa = fi + (Lanes::all(4.0f) * fj + k) * ninth;
          const Lanes bb = l + (fj + Lanes::all(4.0f) * k) * ninth;
          const Lanes ab = Lanes::all(2.0f) * (fj + k) * ninth;
          const Lanes valid = and_mask(less_equal_mask(k, Lanes::all(static_cast<float>(k_max))),
                                       greater_mask(aa * bb - ab * ab, singular));
          push_quad(quads, valid, aa, bb, ab);
        }
      }
  } else {
    for (int i = 0; i <= 16; ++i) {
      const int j_max = 16 - i;
      for (int j0 = 0; j0 <= j_max; j0 += 4) {
        const Lanes j = Lanes::ramp(static_cast<float>(j0));
        const Lanes fi = Lanes::all(static_cast<float>(i));
        const Lanes l = Lanes::all(static_cast<float>(16 - i)) - j;
        const Lanes aa = fi + j * quarter, bb = l + j * quarter, ab = j * quarter;
        const Lanes valid = and_mask(less_equal_mask(j, Lanes::all(static_cast<float>(j_max))),
                                     greater_mask(aa * bb - ab * ab, singular));
        push_quad(quads, valid, aa, bb, ab);
      }
    }
  }
  return quads;
}

const std::vector<PartitionQuad>& quads_for(Bc1Mode mode) {
  static const std::vector<PartitionQuad> four = build_quads(Bc1Mode::four_color);   // thread-safe statics
  static const std::vector<PartitionQuad> three = build_quads(Bc1Mode::three_color);
  return mode == Bc1Mode::four_color ? four : three;
}

}  // namespace

ColorCandidate cluster_fit(const ColorBlock& block, const std::array<float, 3>& axis, Bc1Mode mode) {
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
  // Prefix sums per channel, padded to 20 with the total so that 4-lane loads past index 16 stay in bounds.
  float prefix[3][20];
  for (int channel = 0; channel < 3; ++channel) {
    prefix[channel][0] = 0.0f;
    for (int n = 0; n < 16; ++n) prefix[channel][n + 1] = prefix[channel][n] + block.texels[order[n]][channel];
    for (int n = 17; n < 20; ++n) prefix[channel][n] = prefix[channel][16];
  }
  const float totals[3] = {prefix[0][16], prefix[1][16], prefix[2][16]};
  const Lanes third = Lanes::all(1.0f / 3.0f), half = Lanes::all(0.5f);
  const PartitionQuad* quad = quads_for(mode).data();
  BestPartition best;
  if (mode == Bc1Mode::four_color) {
    // i texels on alpha 1, j on 2/3, k on 1/3, l = 16 - i - j - k on 0.
    for (int i = 0; i <= 16; ++i)
      for (int j = 0; i + j <= 16; ++j)
        for (int k0 = 0; k0 <= 16 - i - j; k0 += 4, ++quad) {
          Lanes alpha_x[3];
          for (int channel = 0; channel < 3; ++channel)
            alpha_x[channel] = (Lanes::all(prefix[channel][i] + prefix[channel][i + j]) +
                                Lanes::load(&prefix[channel][i + j + k0])) * third;
          score_lanes(block, *quad, alpha_x, totals, best);
        }
  } else {
    // i texels on alpha 1, j on 1/2, l = 16 - i - j on 0.
    for (int i = 0; i <= 16; ++i)
      for (int j0 = 0; j0 <= 16 - i; j0 += 4, ++quad) {
        Lanes alpha_x[3];
        for (int channel = 0; channel < 3; ++channel)
          alpha_x[channel] = (Lanes::all(prefix[channel][i]) + Lanes::load(&prefix[channel][i + j0])) * half;
        score_lanes(block, *quad, alpha_x, totals, best);
      }
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
