// Chrominance encoding of a `munkberg` block: shape fitting through the solver library (Munkberg et al. 2008,
// section 7.1: "The error is evaluated for the best fit of each template shape, and we select the shape with the
// smallest overall error"), the lattice polish of the base colours ("we search in a small radius of quantized
// values around each base point") and the per-texel (shape I) or per-pair (shape II) 2-bit indices.
//
// Each (mode, shape) is one core ShapeFitProblem (core/shape_fit_problem.h) on the 7-bit base-colour lattice, with
// the linear error of eq. 11 or the stretched error of section 7.2 (f(x) = x^alpha). Shape II's subsampled groups are
// fitted as their mean chroma with weight = number of non-black texels in the pair: for the linear error this is the
// exact group error up to a constant (sum_i |p_i - L|^2 = 2 |mean - L|^2 + scatter); for the stretched error it is an
// approximation, and the final indices are chosen on the texels themselves.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "core/shape_fit_problem.h"
#include "formats/munkberg/munkberg_layout.h"
#include "formats/munkberg/munkberg_log_error.h"
#include "formats/munkberg/munkberg_shapes.h"
#include "solvers/solver.h"

namespace blocklab::munkberg {

struct ChromaSettings {
  const Solver* solver = nullptr;        // the shape-fit solver (procrustes when null)
  SolverOptions solver_options;          // resolved for `solver`
  // Non-procrustes solvers start from the Procrustes answer (warm start) instead of their own default start.
  bool warm_start = true;
  bool polish = true;                    // lattice polish of the base colours (section 7.1)
  SolverOptions polish_options;          // resolved lattice_polish options
  int polish_candidates = 2;             // how many of the best-ranked shapes are polished (0 = all)
  // Error the polish minimises and the final shape choice compares: `fit` = the shape-fit error itself, `log2rgb` =
  // the block's reconstruction error in log2[RGB] (munkberg_log_error.h; needs the decoded luminance).
  enum class PolishError { fit, log2rgb } polish_error = PolishError::log2rgb;
  ShapeErrorKind error_kind = ShapeErrorKind::stretched;
  double alpha = kDefaultStretchExponent;
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
  double polish_error = 0.0;                       // the error the shape was chosen by (fit or log2rgb)
};

// The shape-fit problem data of `mode` and `shape` for `points` (group means for shape II). `has_weight` is false
// when every texel has weight 0 (nothing to fit).
ShapeFitData chroma_fit_data(const ChromaPoints& points, Mode mode, const ShapeTemplate& shape,
                             const ChromaSettings& settings, bool* has_weight);

// Solves one (mode, shape) problem: solver (+ warm start), snap to the lattice. Returns the lattice codes and the
// problem error there. `seed` is the stream seed of this solve.
struct ShapeSolve {
  std::array<int, kBaseCoordinateCount> base{};
  double error = 0.0;
};
ShapeSolve solve_shape(const ShapeFitProblem& problem, const ChromaSettings& settings, std::uint64_t seed);

// Best index per chroma group for the decoded landmarks of (shape, base), in the settings' error (linear or
// stretched), summed over the group's texels with their weights; ties keep the lower landmark.
std::array<std::uint8_t, kTexels> assign_chroma_indices(const ChromaPoints& points, Mode mode,
                                                        const ShapeTemplate& shape,
                                                        const std::array<int, kBaseCoordinateCount>& base,
                                                        const ChromaSettings& settings);

// The solver answers of the 8 shape problems of one (points, mode): the shape-fit problems do not depend on the
// luminance, so modes that share a chroma layout on the same points (shape I and two-plane) can share them.
struct ShapeSolveCache {
  bool valid = false;
  Mode mode = Mode::shape_i;
  std::array<ShapeSolve, kShapeCount> solves{};
};

// The whole chroma search of one mode: every shape solved with the fit error, the shapes ranked by the polish error
// at their solver answers (log2rgb: `log_targets` must be given; fit: the fit error), the best `polish_candidates`
// polished in that error, the lowest kept, indices assigned in the fit error. `block_seed` is the block's stream seed (each (mode, shape) solve derives its own).
// `cache` (optional): when valid for `mode`, its solves are used instead of solving again (the caller guarantees the
// same points, settings and block_seed); otherwise it is filled.
ChromaFit fit_chroma(const ChromaPoints& points, Mode mode, const ShapeSet& shapes, const ChromaSettings& settings,
                     std::uint64_t block_seed, const ChromaLogTargets* log_targets = nullptr,
                     ShapeSolveCache* cache = nullptr);

}  // namespace blocklab::munkberg
