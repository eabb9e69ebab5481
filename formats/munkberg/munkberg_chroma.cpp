// Chrominance shape fitting of the `munkberg` format through the solver library (formats/munkberg/munkberg_chroma.h;
// Munkberg et al. 2008, sections 7.1 and 7.2).
#include "formats/munkberg/munkberg_chroma.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "core/error.h"
#include "formats/munkberg/munkberg_block.h"
#include "solvers/lattice_polish/lattice_polish_solver.h"
#include "solvers/procrustes/procrustes_solver.h"
#include "solvers/seeding.h"

namespace blocklab::munkberg {

namespace {

// Lattice codes of a solver answer: its lattice indices when it returned them, otherwise the nearest lattice point of
// each parameter (continuous solvers such as nlopt).
std::array<int, kBaseCoordinateCount> lattice_codes(const Problem& problem, const SolveResult& result) {
  std::array<int, kBaseCoordinateCount> codes{};
  for (int p = 0; p < kBaseCoordinateCount; ++p) {
    const std::size_t pp = static_cast<std::size_t>(p);
    std::int64_t index = kBaseCoordinateMax / 2;   // no usable answer (a failed solve): the lattice centre
    if (result.lattice_indices.size() == static_cast<std::size_t>(kBaseCoordinateCount))
      index = result.lattice_indices[pp];
    else if (result.parameters.size() == static_cast<std::size_t>(kBaseCoordinateCount) &&
             std::isfinite(result.parameters[pp]))   // NaN never reaches nearest_index's integer conversion
      index = problem.lattice(p).nearest_index(result.parameters[pp]);
    codes[pp] = static_cast<int>(std::min<std::int64_t>(kBaseCoordinateMax, std::max<std::int64_t>(0, index)));
  }
  return codes;
}

std::array<double, kBaseCoordinateCount> lattice_point(const Problem& problem,
                                                       const std::array<int, kBaseCoordinateCount>& codes) {
  std::array<double, kBaseCoordinateCount> x{};
  for (int p = 0; p < kBaseCoordinateCount; ++p)
    x[static_cast<std::size_t>(p)] = problem.lattice(p).point(codes[static_cast<std::size_t>(p)]);
  return x;
}

double point_distance(const ChromaSettings& settings, const Point2& p, double lu, double lv) {
  if (settings.error_kind == ShapeErrorKind::linear) return (p.u - lu) * (p.u - lu) + (p.v - lv) * (p.v - lv);
  // Section 7.2: the distance after f(c) = max(c, floor)^alpha on both sides.
  const double du = ShapeFitError::stretch(p.u, settings.alpha) - ShapeFitError::stretch(lu, settings.alpha);
  const double dv = ShapeFitError::stretch(p.v, settings.alpha) - ShapeFitError::stretch(lv, settings.alpha);
  return du * du + dv * dv;
}

}  // namespace

ShapeFitData chroma_fit_data(const ChromaPoints& points, Mode mode, const ShapeTemplate& shape,
                             const ChromaSettings& settings, bool* has_weight) {
  ShapeFitData data;
  data.shape = shape;
  data.error_kind = settings.error_kind;
  data.exponent = settings.alpha;
  data.lattice_bits = kBaseCoordinateBits;
  const int groups = chroma_groups(mode);
  data.points.assign(static_cast<std::size_t>(groups), Point2{});
  data.weights.assign(static_cast<std::size_t>(groups), 0.0);
  double total = 0.0;
  for (int g = 0; g < groups; ++g) {
    double su = 0.0, sv = 0.0, sw = 0.0, plain_u = 0.0, plain_v = 0.0;
    int count = 0;
    for (int i = 0; i < kTexels; ++i) {
      if (chroma_group_of_texel(mode, i) != g) continue;
      const std::size_t ii = static_cast<std::size_t>(i);
      su += points.weight[ii] * points.point[ii].u;
      sv += points.weight[ii] * points.point[ii].v;
      sw += points.weight[ii];
      plain_u += points.point[ii].u;
      plain_v += points.point[ii].v;
      ++count;
    }
    const std::size_t gg = static_cast<std::size_t>(g);
    // A group without weight (all its texels black) still needs a valid point: the plain mean, weight 0.
    data.points[gg] = sw > 0.0 ? Point2{su / sw, sv / sw} : Point2{plain_u / count, plain_v / count};
    // Means of points in [0, 1] stay in [0, 1] up to rounding; clamp so validation never sees 1 + ulp.
    data.points[gg].u = std::min(1.0, std::max(0.0, data.points[gg].u));
    data.points[gg].v = std::min(1.0, std::max(0.0, data.points[gg].v));
    data.weights[gg] = sw;
    total += sw;
  }
  if (has_weight != nullptr) *has_weight = total > 0.0;
  return data;
}

ShapeSolve solve_shape(const ShapeFitProblem& problem, const ChromaSettings& settings, std::uint64_t seed) {
  const Solver& procrustes = procrustes_solver();
  const Solver& solver = settings.solver != nullptr ? *settings.solver : procrustes;
  SolveResult result;
  if (&solver == &procrustes) {
    result = procrustes.solve(problem, settings.solver_options, nullptr, seed);
  } else if (settings.warm_start) {
    const SolveResult start = procrustes.solve(problem, SolverOptions{}, nullptr, seed);
    const std::array<double, kBaseCoordinateCount> x = lattice_point(problem, lattice_codes(problem, start));
    result = solver.solve(problem, settings.solver_options, x.data(), seed);
  } else {
    result = solver.solve(problem, settings.solver_options, nullptr, seed);
  }
  ShapeSolve out;
  out.base = lattice_codes(problem, result);
  const std::array<double, kBaseCoordinateCount> x = lattice_point(problem, out.base);
  out.error = problem.eval(x.data());
  return out;
}

std::array<std::uint8_t, kTexels> assign_chroma_indices(const ChromaPoints& points, Mode mode,
                                                        const ShapeTemplate& shape,
                                                        const std::array<int, kBaseCoordinateCount>& base,
                                                        const ChromaSettings& settings) {
  const double values[4] = {base_value(base[0]), base_value(base[1]), base_value(base[2]), base_value(base[3])};
  double lu[kShapeLandmarkCount], lv[kShapeLandmarkCount];
  decode_landmarks(shape, values, lu, lv);   // exactly the decoder's landmarks
  std::array<std::uint8_t, kTexels> index{};
  for (int g = 0; g < chroma_groups(mode); ++g) {
    int best = 0;
    double best_error = 0.0;
    for (int k = 0; k < kShapeLandmarkCount; ++k) {
      double error = 0.0;
      for (int i = 0; i < kTexels; ++i) {
        if (chroma_group_of_texel(mode, i) != g) continue;
        const std::size_t ii = static_cast<std::size_t>(i);
        error += points.weight[ii] * point_distance(settings, points.point[ii], lu[k], lv[k]);
      }
      if (k == 0 || error < best_error) {   // strict: ties keep the lower landmark
        best = k;
        best_error = error;
      }
    }
    index[static_cast<std::size_t>(g)] = static_cast<std::uint8_t>(best);
  }
  return index;
}

ChromaFit fit_chroma(const ChromaPoints& points, Mode mode, const ShapeSet& shapes, const ChromaSettings& settings,
                     std::uint64_t block_seed, const ChromaLogTargets* log_targets, ShapeSolveCache* cache) {
  ChromaFit fit;
  bool has_weight = false;
  chroma_fit_data(points, mode, shapes.shapes[0], settings, &has_weight);
  if (!has_weight) {
    // Every texel is true black: chroma is never seen. Grey base colours (wb, wr) keep the block well-formed.
    const int grey_u = static_cast<int>(std::lround(kRec601WeightB * kBaseCoordinateMax));
    const int grey_v = static_cast<int>(std::lround(kRec601WeightR * kBaseCoordinateMax));
    fit.base = {grey_u, grey_v, grey_u, grey_v};
    return fit;
  }

  std::vector<ShapeFitProblem> problems;
  problems.reserve(kShapeCount);
  std::array<ShapeSolve, kShapeCount> solves{};
  const bool cached = cache != nullptr && cache->valid && cache->mode == mode;
  for (int s = 0; s < kShapeCount; ++s) {
    problems.push_back(make_shape_fit_problem(
        chroma_fit_data(points, mode, shapes.shapes[static_cast<std::size_t>(s)], settings, nullptr)));
    if (cached) continue;   // the same problems were solved for another mode of this block
    const std::uint64_t seed = derive_stream_seed(block_seed, static_cast<std::uint64_t>(static_cast<int>(mode) * kShapeCount + s));
    solves[static_cast<std::size_t>(s)] = solve_shape(problems.back(), settings, seed);
  }
  if (cached) {
    solves = cache->solves;
  } else if (cache != nullptr) {
    cache->valid = true;
    cache->mode = mode;
    cache->solves = solves;
  }

  // Section 7.1's lattice polish on the best-fitting shapes, then the shape choice in the polish error.
  const bool log_polish = settings.polish_error == ChromaSettings::PolishError::log2rgb;
  if (log_polish && log_targets == nullptr) fail("munkberg", "internal: log2rgb polish without decoded luminance");
  // Rank the shapes by the polish error at their solver answers (one evaluation each), so the polish budget goes
  // to the shapes that reconstruct best; stable, so equal errors keep the lower shape index first.
  std::array<double, kShapeCount> rank_error{};
  std::vector<ErrorProblem<ChromaLogError>> log_problems;
  if (log_polish) log_problems.reserve(kShapeCount);
  for (int s = 0; s < kShapeCount; ++s) {
    const std::size_t ss = static_cast<std::size_t>(s);
    rank_error[ss] = solves[ss].error;
    if (!log_polish) continue;
    log_problems.push_back(make_chroma_log_problem(mode, shapes.shapes[ss], *log_targets));
    const std::array<double, kBaseCoordinateCount> x = lattice_point(log_problems.back(), solves[ss].base);
    rank_error[ss] = log_problems.back().eval(x.data());
  }
  std::array<int, kShapeCount> order{};
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return rank_error[static_cast<std::size_t>(a)] < rank_error[static_cast<std::size_t>(b)];
  });
  const int candidates =
      settings.polish_candidates == 0 ? kShapeCount : std::min(kShapeCount, settings.polish_candidates);
  // interval_bb's answer is already the lattice optimum of the fit error: polishing it in that error is a no-op.
  const bool certified = settings.solver != nullptr && settings.solver->name() == "interval_bb";
  int best = -1;
  double best_error = 0.0;
  ShapeSolve best_solve;
  for (int r = 0; r < candidates; ++r) {
    const std::size_t s = static_cast<std::size_t>(order[static_cast<std::size_t>(r)]);
    ShapeSolve solve = solves[s];
    double error = solve.error;
    if (log_polish) {
      const ErrorProblem<ChromaLogError>& problem = log_problems[s];
      const std::array<double, kBaseCoordinateCount> start = lattice_point(problem, solve.base);
      error = rank_error[s];
      if (settings.polish) {
        const SolveResult polished = lattice_polish_solver().solve(problem, settings.polish_options, start.data(), 0);
        const std::array<int, kBaseCoordinateCount> codes = lattice_codes(problem, polished);
        const std::array<double, kBaseCoordinateCount> x = lattice_point(problem, codes);
        const double polished_error = problem.eval(x.data());
        // Only a strictly better lattice point replaces the solver's answer.
        if (polished_error < error) {
          error = polished_error;
          solve.base = codes;
          solve.error = problems[s].eval(x.data());
        }
      }
    } else if (settings.polish && !certified) {
      const std::array<double, kBaseCoordinateCount> start = lattice_point(problems[s], solve.base);
      const SolveResult polished = lattice_polish_solver().solve(problems[s], settings.polish_options, start.data(), 0);
      const std::array<int, kBaseCoordinateCount> codes = lattice_codes(problems[s], polished);
      const std::array<double, kBaseCoordinateCount> x = lattice_point(problems[s], codes);
      const double polished_error = problems[s].eval(x.data());
      if (polished_error < error) solve = ShapeSolve{codes, polished_error};
      error = solve.error;
    }
    // Strict: ties keep the candidate ranked first.
    if (best < 0 || error < best_error) {
      best = static_cast<int>(s);
      best_error = error;
      best_solve = solve;
    }
  }
  fit.shape = best;
  fit.base = best_solve.base;
  fit.fit_error = best_solve.error;
  fit.polish_error = best_error;
  fit.index = assign_chroma_indices(points, mode, shapes.shapes[static_cast<std::size_t>(best)], fit.base, settings);
  return fit;
}

}  // namespace blocklab::munkberg
