// The fit of (alpha, Lwhite) for Banterle et al. 2008 (section 3.1: "The parameters that are optimized ... are alpha
// and Lwhite, which are initialized using automatic estimation as presented in [22]"): eq. 3 on the luminance
// histogram (tmo_fit_problem.h), started at the Reinhard 2002 estimate (reinhard_estimate.h), solved by a solver
// of the library (solvers/registry.h find_solver). Format option `fit`:
//   none          the Reinhard 2002 estimate, no search
//   coeff_search  coeff_search grid (9 x 9, 3 zooms) + coordinate hill climbing on eq. 3 (SPECS.md section 5 item 2)
//   nlopt         NLopt (default LN_SBPLX, 400 evaluations, initial step 5 % of the box: about 1 stop, many
//                 quantisation levels, SPECS.md section 5 item 2; e.g. algorithm=GN_DIRECT_L for a global search)
//   ceres_lm      (default; the paper's Levenberg-Marquardt) ceres_lm on the smooth surrogate, then an LN_SBPLX polish
//                 on eq. 3 (400 evaluations, initial step 1 % of the box) from the LM result, or from the estimate
//                 when that is better on eq. 3 (SPECS.md section 5 item 3)
//   ceres_lm_raw  ceres_lm directly on eq. 3's residuals: the Jacobian has every 8-bit code frozen (round has a zero
//                 derivative), the SPECS.md section 5 failure mode, kept to show it.
// Format option `fit_options`: "key=value, key=value" for the solver the method names (tmo_fit_solver_name), with
// that solver's own keys, the spelling of the BC formats' `solver_options` (formats/common/block_solver.h). They
// override the method's defaults above; for ceres_lm they configure the LM stage (the polish is fixed). `none`
// takes no options. (This replaces the options fit_algorithm and fit_evaluations of format revision 1:
// fit_algorithm=X is fit_options "algorithm=X", fit_evaluations=N is "max_evaluations=N".)
// Box: log2 alpha in [log2 alpha0 - 10, log2 alpha0 + 10], log2 Lwhite in [-8, 20]: Lwhite <= 2^20 keeps the lowest
// non-zero LUT entry a normal half (itmo_lut.h: entry 1 ~ 2^15 / (255 Lwhite)). The estimate is clamped into it.
// The answer is the better, on eq. 3, of the solver's result and the (clamped) estimate, so a fit is never worse
// than its start; `solver_improved` says whether the solver beat the estimate.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "formats/banterle/reinhard_estimate.h"
#include "formats/banterle/tmo_fit_problem.h"
#include "solvers/solver.h"

namespace blocklab {

enum class TmoFitMethod { none, coeff_search, nlopt, ceres_lm, ceres_lm_raw };

// Option text <-> method; parse throws Error naming `who` and the valid names.
TmoFitMethod parse_tmo_fit_method(const std::string& text, const std::string& who);
const std::vector<std::string>& tmo_fit_method_names();

constexpr double kTmoLog2WhiteMin = -8.0;
constexpr double kTmoLog2WhiteMax = 20.0;
constexpr double kTmoLog2AlphaRadius = 10.0;

struct TmoFitSettings {
  TmoFitMethod method = TmoFitMethod::ceres_lm;
  SolverOptions solver_options;   // given for the method's solver (unresolved; the method's defaults fill the rest)
  std::uint64_t seed = 1;
};

// The registry solver a method runs ("" for none; ceres_lm: the LM stage).
std::string tmo_fit_solver_name(TmoFitMethod method);

// "key=value, key=value" (spaces around items ignored; "" = none) -> options; throws Error("<who>: option
// 'fit_options': ...") on an empty item, an item without '=' or a repeated key.
SolverOptions parse_tmo_fit_options(const std::string& text, const std::string& who);

// The method's defaults overridden by `given`, resolved with the solver's option specs; throws Error naming `who`,
// the key and the valid keys on an unknown key or bad value, and on any option for `none`.
SolverOptions resolve_tmo_fit_options(TmoFitMethod method, const SolverOptions& given, const std::string& who);

struct TmoFitResult {
  ReinhardParameters estimate;    // Reinhard 2002, clamped into the box
  ReinhardParameters fitted;      // the answer
  double estimate_error = 0.0;    // eq. 3 (histogram) at the estimate
  double fitted_error = 0.0;      // eq. 3 (histogram) at the answer
  bool solver_improved = false;   // the solver's result beat the estimate strictly
  std::vector<Summary> summaries; // one per solver run, in order (empty for `none`)
};

Bounds tmo_fit_bounds(const ReinhardParameters& estimate);
// Clamps Lwhite into the box's range (alpha is the box centre, so it is always inside).
ReinhardParameters clamp_to_fit_box(ReinhardParameters parameters);

// eq. 3 (histogram) at given parameters.
double tmo_fit_error(const LuminanceHistogram& histogram, const ReinhardParameters& parameters);

TmoFitResult fit_tmo_parameters(const LuminanceHistogram& histogram, const ReinhardParameters& estimate,
                                const TmoFitSettings& settings);

}  // namespace blocklab
