// The pair bound of the shape fit's box enclosure (formats/munkberg/shape_fit/shape_fit_problem.h,
// ShapeFitError::box_enclosure; the interval branch-and-bound of Munkberg et al. 2008 section 7.1 prunes with it).
//
// WHY. The natural extension bounds every point on its own: point i pays at least min_k min_{x in box} d_ik(x), the
// distance from its target to the nearest landmark's range over the box. When the box is large against the shape
// (a small shape, or the first levels of the search), every point finds some landmark range close by and the sum is
// far below the error at any single x of the box: measured on real blocks, boxes of 2^8-2^11 lattice points that
// the enclosure could not discard had a median true minimum 1.3-1.6x the certified optimum. The points are coupled
// through the ONE transform x, and the pair bound puts part of that coupling back.
//
// THE BOUND. For two points i, j with weights w_i, w_j > 0 and any x:
//     w_i min_k d_ik(x) + w_j min_l d_jl(x) = min_{k,l} [w_i |a_k|^2 + w_j |b_l|^2],
//     a_k = t_i - M_k(x), b_l = t_j - M_l(x)   (M_k the decoded landmark, stretched for the stretched error),
// and for each (k, l), minimising over a - b = (t_i - t_j) - (M_k(x) - M_l(x)) fixed,
//     w_i |a|^2 + w_j |b|^2 >= w_i w_j / (w_i + w_j) |(t_i - t_j) - (M_k(x) - M_l(x))|^2
//                          >= w_i w_j / (w_i + w_j) dist(t_i - t_j, D_kl)^2,
// with D_kl an enclosure of M_k - M_l over the box (per coordinate; exactly 0 for k == l: two points on one landmark
// pay half their squared distance). Each (k, l) term is also at least the two points' own natural bounds. Disjoint
// pairs add up. Far-apart points cannot both lie on landmarks unless two landmarks are that far apart, which the box
// may forbid.
//
// WHICH PAIRS. The pairs must be disjoint; which ones is a free choice that only changes the bound's strength.
// ShapeFitError::pair_order lists the weighted points sorted on the coordinate with the larger spread; a box pairs
// the r-th and the (r + m/2)-th of its m points that have several possibly-nearest landmarks (single-candidate
// points are bounded by the tangent plane instead). Measured on 20 certified blocks each of Desk.exr and
// memorial.hdr (linear error, all weighted points paired, docs/solver-bench.md): interval_bb boxes 7,681 -> 2,793
// and 6,353 -> 2,826 per block; pairing the extremes (r with m - 1 - r) or greedily the farthest pairs left
// 3,128-3,285.
#pragma once

#include "formats/munkberg/shape_fit/shape_fit_problem.h"

namespace blocklab::shape_fit_detail {

// Enclosures [lower, upper] over a box of the differences M_k - M_l between decoded landmark coordinates, u and v,
// per ordered landmark pair (k, l); k == l is exactly 0.
struct LandmarkDifferences {
  double u_lower[kShapeLandmarkCount][kShapeLandmarkCount] = {};
  double u_upper[kShapeLandmarkCount][kShapeLandmarkCount] = {};
  double v_lower[kShapeLandmarkCount][kShapeLandmarkCount] = {};
  double v_upper[kShapeLandmarkCount][kShapeLandmarkCount] = {};

  // Sets the enclosure of M_k - M_l (coordinate u or v) and, negated, that of M_l - M_k.
  void set(int k, int l, bool u_coordinate, double lower, double upper);
};

// Lower bound, over the box, of w_i min_k d_ik + w_j min_l d_jl for the points i and j (targets as the error stores
// them), given each point's per-landmark natural lower bounds (unweighted; candidate_lower[k]) and the landmark
// differences. Rounded down; >= 0. NaN inputs give a NaN-free value only if the caller has excluded them.
double pair_lower_bound(const ShapeFitError& error, int i, int j, const double* i_lower, const double* j_lower,
                        const LandmarkDifferences& differences);

}  // namespace blocklab::shape_fit_detail
