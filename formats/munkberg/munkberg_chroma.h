// Chrominance encoding of a `munkberg` block: shape fitting through the solver library (Munkberg et al. 2008,
// section 7.1: "The error is evaluated for the best fit of each template shape, and we select the shape with the
// smallest overall error"), the lattice polish of the base colours ("we search in a small radius of quantized
// values around each base point") and the per-texel (shape I) or per-pair (shape II) 2-bit indices.
//
// Each (mode, shape) is one core ShapeFitProblem (formats/munkberg/shape_fit/shape_fit_problem.h) on the 7-bit
// base-colour lattice, with the linear error of eq. 11 or the stretched error of section 7.2 (f(x) = x^alpha). Shape
// II's subsampled groups are fitted as their mean chroma with weight = number of non-black texels in the pair: for the
// linear error this is the exact group error up to a constant (sum_i |p_i - L|^2 = 2 |mean - L|^2 + scatter); for the
// stretched error it is an approximation, and the final indices are chosen on the texels themselves.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "formats/munkberg/shape_fit/shape_fit_problem.h"
#include "formats/munkberg/munkberg_base_colour_sums.h"
#include "formats/munkberg/munkberg_layout.h"
#include "formats/munkberg/munkberg_log_error.h"
#include "formats/munkberg/munkberg_shapes.h"
#include "formats/munkberg/shape_fit/procrustes_templates.h"
#include "solvers/procrustes/procrustes_workspace.h"
#include "solvers/solver.h"

namespace blocklab::munkberg {

struct ChromaSettings {
  const Solver* solver = nullptr;        // the shape-fit solver (procrustes when null)
  SolverOptions solver_options;          // resolved for `solver`
  // The global search's Procrustes options, parsed from solver_options once per texture (parsing them per block cost
  // ~5k instructions); when absent, the search parses solver_options itself.
  std::optional<ProcrustesOptions> procrustes_options;
  // Non-procrustes solvers start from the Procrustes answer (warm start) instead of their own default start.
  bool warm_start = true;
  bool polish = true;                    // lattice polish of the base colours (section 7.1)
  SolverOptions polish_options;          // resolved lattice_polish options
  int polish_candidates = 2;             // how many of the best-ranked shapes are polished (0 = all)
  // ChromaFit::index in the fit error; false when the caller chooses the indices itself (the encoder's default
  // log2rgb index metric), which leaves ChromaFit::index all 0.
  bool fit_indices = true;
  // Global search, log2rgb polish error: a candidate is evaluated only up to the error that could bring its shape
  // into the `polish_candidates` best (fit_chroma_global). Exact (the same answer with it off; tested), always on in
  // the format; off only to test it.
  bool top_shape_bound = true;
  // Global search: shapes after the first are polished only while their error is within (1 + polish_margin) of the
  // first's (0 = no limit).
  double polish_margin = 0.0;
  // Global search with the log2rgb polish error (EncoderSettings::good_enough; approximate, 0 = off): a shape whose
  // error is already at most this is not polished, and no further shape is polished once one is.
  double good_enough = 0.0;
  // Error the polish minimises and the final shape choice compares: `fit` = the shape-fit error itself, `log2rgb` =
  // the block's reconstruction error in log2[RGB] (munkberg_log_error.h; needs the decoded luminance).
  enum class PolishError { fit, log2rgb } polish_error = PolishError::log2rgb;
  ShapeErrorKind error_kind = ShapeErrorKind::stretched;
  double alpha = kDefaultStretchExponent;
  // How the shapes are searched (option chroma_search):
  //   global     (default; procrustes only) one clustering of the block's points for all 8 shapes, every (shape,
  //              correspondence) candidate ranked together by its Procrustes bound, the best `search_candidates`
  //              (+ ties, up to search_tie_limit more, + each shape's best search_per_shape) snapped and
  //              evaluated in the polish error, the best
  //              `search_refined` of them refined first (formats/munkberg/shape_fit/procrustes_templates.h);
  //   per_shape  every shape solved on its own by the solver (any solver; the only choice for non-procrustes).
  enum class Search { global, per_shape } search = Search::global;
  int search_candidates = 64;
  int search_tie_limit = 16;
  int search_per_shape = 1;   // each shape's own best candidates also evaluated (every shape competes)
  // Skip rule (option skip_constant, global search): a block whose weighted chroma points (group means for shape II)
  // all lie within constant_tolerance (max-norm) of the first weighted one skips the candidate ranking; its chroma
  // is the closed-form scale-0 fit (both base points on the weighted mean). Tolerance 0 = exactly constant chroma
  // (constant blocks, grey or single-hue gradients), where the ranked search gives the same answer.
  bool skip_constant = true;
  double constant_tolerance = 0.0;
  int search_refined = 8;
};

// The chroma of one block's texels: (u, v) in [0, 1]^2 and a weight (0 for true-black texels, 1 otherwise).
struct ChromaPoints {
  std::array<Point2, kTexels> point{};
  std::array<double, kTexels> weight{};
};

struct ChromaFit {
  int shape = 0;
  std::array<int, kBaseCoordinateCount> base{};    // u0, v0, u1, v1 codes
  std::array<std::uint8_t, kTexels> index{};       // per chroma group (unused groups 0)
  double fit_error = 0.0;                          // the ShapeFitProblem error at the stored base colours
                                                   // (per_shape search, or polish_error=fit; else 0)
  double polish_error = 0.0;                       // the error the shape was chosen by (fit or log2rgb)
};

// The shape-fit problem data of `mode` and `shape` for `points` (group means for shape II). `has_weight` is false
// when every texel has weight 0 (nothing to fit).
ShapeFitData chroma_fit_data(const ChromaPoints& points, Mode mode, const ShapeTemplate& shape,
                             const ChromaSettings& settings, bool* has_weight);

// The working buffers of the chroma search, one per worker thread (the block loop owns them and passes them down,
// munkberg_format.cpp): reused across blocks, cleared before each use, so no result depends on what an earlier
// block left in them. Every search given none makes its own.
struct ChromaWorkspace {
  ProcrustesWorkspace procrustes;          // per-shape search: each procrustes solve
  TemplateRankingWorkspace ranking;        // global search: the cross-template ranking
  std::vector<ShapeTemplate> templates;    // global search: the shape set as a template list
  BaseColourSums base_sums;                // global search, log2rgb polish: the base colours' error shares (~35 KB)
};

// Solves one (mode, shape) problem: solver (+ warm start), snap to the lattice. Returns the lattice codes and the
// problem error there. `seed` is the stream seed of this solve.
struct ShapeSolve {
  std::array<int, kBaseCoordinateCount> base{};
  double error = 0.0;
  bool proven_optimal = false;   // the solver proved `base` the lattice optimum of the fit error (Termination::optimal)
};
ShapeSolve solve_shape(const ShapeFitProblem& problem, const ChromaSettings& settings, std::uint64_t seed,
                       ChromaWorkspace* workspace = nullptr);

// Nearest 7-bit lattice codes of continuous base points (each coordinate clamped to [0, 1] first).
std::array<int, kBaseCoordinateCount> snap_base_codes(Point2 base0, Point2 base1);
// The lattice point of base-colour codes (each in 0..kBaseCoordinateMax) on the shape-fit problems' lattice
// (shape_fit_lattices(7)).
std::array<double, kBaseCoordinateCount> base_code_point(const std::array<int, kBaseCoordinateCount>& codes);

// The lattice point (u0, v0, u1, v1) of base-colour codes on `problem`'s lattices.
std::array<double, kBaseCoordinateCount> base_lattice_point(const Problem& problem,
                                                            const std::array<int, kBaseCoordinateCount>& codes);

// Section 7.1's lattice polish (lattice_polish with settings.polish_options) of `codes` in `problem`'s error; a
// strictly lower error than `*error` replaces codes and error (returns true).
bool polish_base_colours(const Problem& problem, const ChromaSettings& settings,
                         std::array<int, kBaseCoordinateCount>* codes, double* error);

// The same polish in a ChromaLogError: lattice_polish's full radius-1 neighbourhood (the default options) through
// polish_log_error_full, its coordinate descent (polish_search=coordinate, or a radius above 1) through
// polish_log_error_coordinate (each the same answer, faster); options outside lattice_polish's ranges through
// lattice_polish on its Problem (which reports them).
// `cache`: as for polish_log_error_full.
bool polish_log_base_colours(const ChromaLogError& error, const ChromaSettings& settings,
                             std::array<int, kBaseCoordinateCount>* codes, double* error_at_codes,
                             BaseColourSums* cache = nullptr);

// Best index per chroma group for the decoded landmarks of (shape, base), in the settings' error (linear or
// stretched), summed over the group's texels with their weights; ties keep the lower landmark.
std::array<std::uint8_t, kTexels> assign_chroma_indices(const ChromaPoints& points, Mode mode,
                                                        const ShapeTemplate& shape,
                                                        const std::array<int, kBaseCoordinateCount>& base,
                                                        const ChromaSettings& settings);

// The Procrustes options of the global search for resolved solver options (defaults when there are none).
inline ProcrustesOptions procrustes_options_of(const SolverOptions& solver_options) {
  return solver_options.empty() ? ProcrustesOptions{} : ProcrustesOptions::from_resolved(solver_options);
}

// The solver answers of the 8 shape problems of one (points, mode): the shape-fit problems do not depend on the
// luminance, so modes that share a chroma layout on the same points (shape I and two-plane) can share them.
// The global search caches its ranked candidates instead (they depend only on the points, not on the luminance).
struct ShapeSolveCache {
  bool valid = false;
  Mode mode = Mode::shape_i;
  std::array<ShapeSolve, kShapeCount> solves{};
  std::vector<TemplateCandidate> ranked;
};

// The whole chroma search of one mode: every shape solved with the fit error, the shapes ranked by the polish error
// at their solver answers (log2rgb: `log_targets` must be given; fit: the fit error), the best `polish_candidates`
// polished in that error, the lowest kept, indices assigned in the fit error. `block_seed` is the block's stream seed
// (each (mode, shape) solve derives its own). `cache` (optional): when valid for `mode`, its solves are used instead of
// solving again (the caller guarantees the same points, settings and block_seed); otherwise it is filled.
// Dispatches to the global search (fit_chroma_global) when settings.search is global and the solver is procrustes.
ChromaFit fit_chroma(const ChromaPoints& points, Mode mode, const ShapeSet& shapes, const ChromaSettings& settings,
                     std::uint64_t block_seed, const ChromaLogTargets* log_targets = nullptr,
                     ShapeSolveCache* cache = nullptr, ChromaWorkspace* workspace = nullptr);

// The global search (munkberg_chroma_global.cpp; ChromaSettings::Search::global): the points must have weight.
// Deterministic (no seed: procrustes is).
ChromaFit fit_chroma_global(const ChromaPoints& points, Mode mode, const ShapeSet& shapes,
                            const ChromaSettings& settings, const ChromaLogTargets* log_targets,
                            ShapeSolveCache* cache, ChromaWorkspace* workspace = nullptr);

// Whether the weighted points of `data` all lie within `tolerance` (max-norm, per coordinate) of the first weighted
// point; `mean` receives their weighted mean (the point itself when they are bit-identical). False without weight.
bool constant_chroma(const ShapeFitData& data, double tolerance, Point2* mean);

// Whether `settings` select the global search (search == global and the solver is procrustes or unset).
bool uses_global_search(const ChromaSettings& settings);

}  // namespace blocklab::munkberg
