// Encoder of the two-plane mode (formats/munkberg/two_plane_encoder.h; Munkberg et al. 2008, section 6.3).
#include "formats/munkberg/two_plane_encoder.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "formats/munkberg/munkberg_luminance.h"

namespace blocklab::munkberg {

namespace {

// The scored log2 luminance of a plane at texel i: kBlackLog2 for a black plane (offset code 0).
double scored(const Plane& p, int i) { return p.offset == 0 ? kBlackLog2 : plane_log_luminance(p, i % 4, i / 4); }

// Best mask for fixed planes (ties: plane 0) and its error.
double assign_mask(const double target[kTexels], TwoPlaneParams* params) {
  double total = 0.0;
  std::uint16_t mask = 0;
  for (int i = 0; i < kTexels; ++i) {
    const double e0 = square(scored(params->plane[0], i) - target[i]);
    const double e1 = square(scored(params->plane[1], i) - target[i]);
    if (e1 < e0) mask = static_cast<std::uint16_t>(mask | (1u << i));
    total += std::min(e0, e1);
  }
  params->mask = mask;
  return total;
}

// Least-squares plane z + a (x - 1.5) + b (y - 1.5) through the texels of `members` (bit i = texel i), quantised.
// All members at or below the half range's bottom: a true-black plane.
Plane fit_plane(const double target[kTexels], std::uint16_t members) {
  double n = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, syy = 0.0, sxy = 0.0, st = 0.0, sxt = 0.0, syt = 0.0;
  bool all_black = true;
  for (int i = 0; i < kTexels; ++i) {
    if (((members >> i) & 1u) == 0u) continue;
    const double x = i % 4 - 1.5, y = i / 4 - 1.5, t = std::max(target[i], kLogLumMin);
    all_black = all_black && target[i] < kLogLumMin;
    n += 1.0; sx += x; sy += y; sxx += x * x; syy += y * y; sxy += x * y; st += t; sxt += x * t; syt += y * t;
  }
  Plane plane;
  if (n == 0.0) return plane;   // empty group: any plane (the mask never selects it); offset 0 = black
  if (all_black) return plane;  // every member below 2^-16: the black plane is exact in the metric's floor
  // Normal equations with a small ridge on the slopes (degenerate groups: one row, one column, a single texel).
  const double ridge = 1e-6;
  double m[3][4] = {{n, sx, sy, st}, {sx, sxx + ridge, sxy, sxt}, {sy, sxy, syy + ridge, syt}};
  for (int c = 0; c < 3; ++c) {   // Gaussian elimination with partial pivoting
    int pivot = c;
    for (int r = c + 1; r < 3; ++r)
      if (std::fabs(m[r][c]) > std::fabs(m[pivot][c])) pivot = r;
    for (int k = 0; k < 4; ++k) std::swap(m[c][k], m[pivot][k]);
    for (int r = 0; r < 3; ++r) {
      if (r == c) continue;
      const double f = m[r][c] / m[c][c];
      for (int k = c; k < 4; ++k) m[r][k] -= f * m[c][k];
    }
  }
  const double z = m[0][3] / m[0][0], a = m[1][3] / m[1][1], b = m[2][3] / m[2][2];
  // Codes: offset >= 1 (0 is the black plane), slopes a = dx / 16 stops per texel, clamped to the fields.
  plane.offset = static_cast<int>(std::min<double>(kPlaneOffsetMax, std::max(1.0, std::round((z - kLogLumMin) * kPlaneOffsetMax / kLogLumRange))));
  plane.dx = static_cast<int>(std::min<double>(kPlaneDeltaMax, std::max<double>(kPlaneDeltaMin, std::round(a * 16.0))));
  plane.dy = static_cast<int>(std::min<double>(kPlaneDeltaMax, std::max<double>(kPlaneDeltaMin, std::round(b * 16.0))));
  return plane;
}

// Fits both planes to a partition, then Lloyd iterations (reassign, refit) while the error drops.
double fit_partition(const double target[kTexels], std::uint16_t mask, TwoPlaneParams* out) {
  TwoPlaneParams params;
  params.mask = mask;
  double best = 0.0;
  bool have = false;
  for (int iteration = 0; iteration < 4; ++iteration) {
    params.plane[0] = fit_plane(target, static_cast<std::uint16_t>(~params.mask));
    params.plane[1] = fit_plane(target, params.mask);
    const double e = assign_mask(target, &params);
    if (have && !(e < best)) break;
    best = e;
    *out = params;
    have = true;
  }
  return best;
}

}  // namespace

double fit_two_plane_luminance(const double target[kTexels], TwoPlaneParams* params) {
  // Candidate partitions: the texels sorted by target, split at every threshold (k = 0: one plane for all).
  std::array<int, kTexels> order{};
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return target[a] < target[b]; });
  double best = 0.0;
  bool have = false;
  std::uint16_t upper = 0xFFFFu;
  for (int k = 0; k < kTexels; ++k) {
    TwoPlaneParams trial;
    const double e = fit_partition(target, upper, &trial);
    if (!have || e < best) {
      best = e;
      *params = trial;
      have = true;
    }
    upper = static_cast<std::uint16_t>(upper & ~(1u << order[static_cast<std::size_t>(k)]));
  }
  // Coordinate descent over the six plane codes with the best mask (strict improvements only: deterministic).
  for (int pass = 0; pass < 3; ++pass) {
    bool improved = false;
    for (int p = 0; p < kPlaneCount; ++p)
      for (int field = 0; field < 3; ++field)
        for (const int sign : {-1, 1}) {
          TwoPlaneParams trial = *params;
          Plane& plane = trial.plane[static_cast<std::size_t>(p)];
          int& code = field == 0 ? plane.offset : field == 1 ? plane.dx : plane.dy;
          const int lo = field == 0 ? 0 : kPlaneDeltaMin, hi = field == 0 ? kPlaneOffsetMax : kPlaneDeltaMax;
          if (code + sign < lo || code + sign > hi) continue;   // outside the field
          code += sign;
          const double e = assign_mask(target, &trial);
          if (e < best) {
            best = e;
            *params = trial;
            improved = true;
          }
        }
    if (!improved) break;
  }
  return best;
}

double two_plane_lower_bound(const BlockTexels& texels, const BlockAnalysis& analysis, const TwoPlaneParams& luminance) {
  bool black[kTexels] = {};
  double decoded_log2[kTexels] = {}, texel_bound[kTexels] = {};
  for (int i = 0; i < kTexels; ++i) {
    const Plane& p = luminance.plane[static_cast<std::size_t>((luminance.mask >> i) & 1u)];
    black[i] = p.offset == 0;
    if (!black[i]) decoded_log2[i] = plane_log_luminance(p, i % 4, i / 4);
  }
  luminance_texel_bounds(texels, analysis, black, decoded_log2, texel_bound);
  double bound = 0.0;
  for (const double term : texel_bound) bound += term;
  return bound * (1.0 - 1e-9);   // as shape_mode_lower_bound: the order of additions cannot lift it above the error
}

TwoPlaneParams encode_two_plane(const BlockTexels& texels, const ShapeSet& shapes, const EncoderSettings& settings,
                                std::uint64_t block_seed, double* error, ShapeSolveCache* cache,
                                ChromaWorkspace* workspace, const TwoPlaneParams* luminance) {
  double log_luminance[kTexels];
  ChromaPoints chroma;
  block_targets(texels, log_luminance, &chroma);
  TwoPlaneParams params;
  if (luminance != nullptr) {
    params = *luminance;
  } else {
    fit_two_plane_luminance(log_luminance, &params);
  }

  ChromaLogTargets targets;
  targets.source_log2 = texel_log2(texels);
  for (int i = 0; i < kTexels; ++i) {
    const std::size_t ii = static_cast<std::size_t>(i);
    const Plane& p = params.plane[static_cast<std::size_t>((params.mask >> i) & 1u)];
    targets.black[ii] = p.offset == 0;   // a black plane decodes to 0 whatever the chroma
    targets.log2_luminance[ii] = p.offset == 0 ? kBlackLog2 : plane_log_luminance(p, i % 4, i / 4);
  }
  // Shape I's chroma: one index per texel, the same shape-fit search with the same streams as shape I (the shape-fit
  // problems do not depend on the luminance), so shape I's solves of this block can be reused through `cache`.
  const ChromaFit fit =
      fit_chroma(chroma, Mode::shape_i, shapes, settings.chroma, block_seed, &targets, cache, workspace);
  params.shape = fit.shape;
  params.base = fit.base;
  params.chroma_index = fit.index;
  if (settings.index_metric == IndexMetric::log2rgb) {
    // Per texel the landmark whose decoded texel has the smallest log2[RGB] error (decoded through the decoder).
    std::array<BlockTexels, kShapeLandmarkCount> decoded;
    for (int k = 0; k < kShapeLandmarkCount; ++k) {
      TwoPlaneParams trial = params;
      trial.chroma_index.fill(static_cast<std::uint8_t>(k));
      decoded[static_cast<std::size_t>(k)] = decode_two_plane_params(trial, shapes);
    }
    for (int i = 0; i < kTexels; ++i) {
      int best = 0;
      double best_error = 0.0;
      for (int k = 0; k < kShapeLandmarkCount; ++k) {
        double e = 0.0;
        for (int c = 0; c < 3; ++c)
          e += square(metric_log2(decoded[static_cast<std::size_t>(k)].rgba[i][c]) -
                      targets.source_log2[static_cast<std::size_t>(i)][static_cast<std::size_t>(c)]);
        if (k == 0 || e < best_error) {   // ties keep the lower landmark
          best = k;
          best_error = e;
        }
      }
      params.chroma_index[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(best);
    }
  }
  canonicalize_mask_anchor(&params);   // texel 0 on plane 0: the stored orientation (same decoded texels)
  if (error != nullptr) *error = block_log2_error(texels, decode_two_plane_params(params, shapes));
  return params;
}

}  // namespace blocklab::munkberg
