// Chrominance shape fitting of the `munkberg` format through the solver library (formats/munkberg/munkberg_chroma.h;
// Munkberg et al. 2008, sections 7.1 and 7.2).
#include "formats/munkberg/munkberg_chroma.h"

#include <algorithm>
#include <climits>
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

// The 7-bit base-colour lattices (the shape-fit problem's; snapping must match the problems' lattice points).
const std::vector<Lattice>& base_lattices() {
  static const std::vector<Lattice> lattices = shape_fit_lattices(kBaseCoordinateBits);
  return lattices;
}

}  // namespace

// Nearest lattice codes of continuous base points (clamped to [0, 1] first: Procrustes transforms may leave it).
std::array<int, kBaseCoordinateCount> snap_base_codes(Point2 base0, Point2 base1) {
  const double values[kBaseCoordinateCount] = {base0.u, base0.v, base1.u, base1.v};
  std::array<int, kBaseCoordinateCount> codes{};
  for (int p = 0; p < kBaseCoordinateCount; ++p) {
    // A NaN coordinate (cannot come from finite points) would make nearest_index's integer conversion undefined:
    // the lattice centre stands in.
    const double v = values[p];
    const std::int64_t index = std::isfinite(v)
                                   ? base_lattices()[static_cast<std::size_t>(p)].nearest_index(std::min(1.0, std::max(0.0, v)))
                                   : kBaseCoordinateMax / 2;
    codes[static_cast<std::size_t>(p)] =
        static_cast<int>(std::min<std::int64_t>(kBaseCoordinateMax, std::max<std::int64_t>(0, index)));
  }
  return codes;
}

std::array<double, kBaseCoordinateCount> base_code_point(const std::array<int, kBaseCoordinateCount>& codes) {
  // Every code's lattice point once (the same Lattice::point values; the polish asks for ~10^3 points per block).
  using CodePoints = std::array<std::array<double, kBaseCoordinateMax + 1>, kBaseCoordinateCount>;
  static const CodePoints points = [] {
    CodePoints table{};
    for (int p = 0; p < kBaseCoordinateCount; ++p)
      for (int code = 0; code <= kBaseCoordinateMax; ++code)
        table[static_cast<std::size_t>(p)][static_cast<std::size_t>(code)] =
            base_lattices()[static_cast<std::size_t>(p)].point(code);
    return table;
  }();
  std::array<double, kBaseCoordinateCount> x{};
  for (int p = 0; p < kBaseCoordinateCount; ++p)
    x[static_cast<std::size_t>(p)] =
        points[static_cast<std::size_t>(p)][static_cast<std::size_t>(codes[static_cast<std::size_t>(p)])];
  return x;
}

std::array<double, kBaseCoordinateCount> base_lattice_point(const Problem& problem,
                                                            const std::array<int, kBaseCoordinateCount>& codes) {
  std::array<double, kBaseCoordinateCount> x{};
  for (int p = 0; p < kBaseCoordinateCount; ++p)
    x[static_cast<std::size_t>(p)] = problem.lattice(p).point(codes[static_cast<std::size_t>(p)]);
  return x;
}

bool polish_base_colours(const Problem& problem, const ChromaSettings& settings,
                         std::array<int, kBaseCoordinateCount>* codes, double* error) {
  const std::array<double, kBaseCoordinateCount> start = base_lattice_point(problem, *codes);
  const SolveResult polished = lattice_polish_solver().solve(problem, settings.polish_options, start.data(), 0);
  const std::array<int, kBaseCoordinateCount> next = lattice_codes(problem, polished);
  const double polished_error = problem.eval(base_lattice_point(problem, next).data());
  // Only a strictly better lattice point replaces the start (NaN never does).
  if (!(polished_error < *error)) return false;
  *codes = next;
  *error = polished_error;
  return true;
}

bool polish_log_base_colours(const ChromaLogError& error, const ChromaSettings& settings,
                             std::array<int, kBaseCoordinateCount>* codes, double* error_at_codes,
                             BaseColourSums* cache) {
  // lattice_polish's defaults for keys the settings do not name (resolved settings name all of them).
  const LatticePolishOptions defaults;
  const auto number = [&](const char* key, long long fallback) {
    const auto it = settings.polish_options.find(key);
    return it == settings.polish_options.end() ? fallback : std::stoll(it->second);
  };
  const long long radius = number("radius", defaults.radius);
  const long long passes = number("max_passes", defaults.max_passes);
  const long long limit = number("full_neighbourhood_limit", defaults.full_neighbourhood_limit);
  // Options lattice_polish accepts (others go to it, which names the bad one), with a radius inside the 7-bit
  // lattice: 3^4 = 81 points, so lattice_polish searches the full neighbourhood when the limit allows it at radius 1,
  // and otherwise runs its coordinate descent.
  if (passes >= 1 && passes <= INT_MAX && limit >= 1 && radius >= 1 && radius <= kBaseCoordinateMax) {
    if (radius == 1 && limit >= 81)
      return polish_log_error_full(error, static_cast<int>(passes), codes, error_at_codes, cache);
    return polish_log_error_coordinate(error, static_cast<int>(radius), static_cast<int>(passes), codes,
                                       error_at_codes, cache);
  }
  const ErrorProblem<ChromaLogError> problem =
      make_problem(error, shape_fit_bounds(), shape_fit_lattices(kBaseCoordinateBits));
  return polish_base_colours(problem, settings, codes, error_at_codes);
}

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

ShapeSolve solve_shape(const ShapeFitProblem& problem, const ChromaSettings& settings, std::uint64_t seed,
                       ChromaWorkspace* workspace) {
  const Solver& procrustes = procrustes_solver();
  const Solver& solver = settings.solver != nullptr ? *settings.solver : procrustes;
  SolveResult result;
  if (&solver == &procrustes) {
    // The registry's solve with the worker's buffers (procrustes_solver.h: the same options, the same answer).
    const ProcrustesOptions options =
        settings.procrustes_options ? *settings.procrustes_options : procrustes_options_of(settings.solver_options);
    result = solve_procrustes(problem, options, nullptr, seed, workspace != nullptr ? &workspace->procrustes : nullptr);
  } else if (settings.warm_start) {
    const SolveResult start = procrustes.solve(problem, SolverOptions{}, nullptr, seed);
    const std::array<double, kBaseCoordinateCount> x = base_lattice_point(problem, lattice_codes(problem, start));
    result = solver.solve(problem, settings.solver_options, x.data(), seed);
  } else {
    result = solver.solve(problem, settings.solver_options, nullptr, seed);
  }
  ShapeSolve out;
  out.base = lattice_codes(problem, result);
  const std::array<double, kBaseCoordinateCount> x = base_lattice_point(problem, out.base);
  out.error = problem.eval(x.data());
  out.proven_optimal = result.summary.termination == Termination::optimal;
  return out;
}

std::array<std::uint8_t, kTexels> assign_chroma_indices(const ChromaPoints& points, Mode mode,
                                                        const ShapeTemplate& shape,
                                                        const std::array<int, kBaseCoordinateCount>& base,
                                                        const ChromaSettings& settings) {
  const double values[4] = {base_value(base[0]), base_value(base[1]), base_value(base[2]), base_value(base[3])};
  double lu[kShapeLandmarkCount], lv[kShapeLandmarkCount];
  decode_landmarks(shape, values, lu, lv);   // exactly the decoder's landmarks
  // The distances' coordinates after the error's map (the stretch f(c) = max(c, floor)^alpha of section 7.2, or the
  // identity for the linear error), once per landmark and per texel instead of once per (texel, landmark) pair: the
  // same pow values, so the same distances bit for bit.
  const bool stretched = settings.error_kind != ShapeErrorKind::linear;
  const auto mapped = [&](double c) { return stretched ? ShapeFitError::stretch(c, settings.alpha) : c; };
  double landmark_u[kShapeLandmarkCount], landmark_v[kShapeLandmarkCount];
  for (int k = 0; k < kShapeLandmarkCount; ++k) {
    landmark_u[k] = mapped(lu[k]);
    landmark_v[k] = mapped(lv[k]);
  }
  double point_u[kTexels], point_v[kTexels];
  for (int i = 0; i < kTexels; ++i) {
    point_u[i] = mapped(points.point[static_cast<std::size_t>(i)].u);
    point_v[i] = mapped(points.point[static_cast<std::size_t>(i)].v);
  }
  std::array<std::uint8_t, kTexels> index{};
  for (int g = 0; g < chroma_groups(mode); ++g) {
    int best = 0;
    double best_error = 0.0;
    for (int k = 0; k < kShapeLandmarkCount; ++k) {
      double error = 0.0;
      for (int i = 0; i < kTexels; ++i) {
        if (chroma_group_of_texel(mode, i) != g) continue;
        const double du = point_u[i] - landmark_u[k], dv = point_v[i] - landmark_v[k];
        error += points.weight[static_cast<std::size_t>(i)] * (du * du + dv * dv);
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

bool constant_chroma(const ShapeFitData& data, double tolerance, Point2* mean) {
  const Point2* first = nullptr;
  double su = 0.0, sv = 0.0, sw = 0.0;
  bool identical = true;
  for (std::size_t i = 0; i < data.points.size(); ++i) {
    const double w = data.weights[i];
    if (!(w > 0.0)) continue;   // weightless (black) points carry no chroma
    const Point2& p = data.points[i];
    if (first == nullptr) first = &p;
    if (std::abs(p.u - first->u) > tolerance || std::abs(p.v - first->v) > tolerance) return false;
    identical = identical && p.u == first->u && p.v == first->v;
    su += w * p.u;
    sv += w * p.v;
    sw += w;
  }
  if (first == nullptr) return false;
  // Bit-identical points: the point itself (a weighted mean could differ from it by rounding).
  *mean = identical ? *first : Point2{std::min(1.0, std::max(0.0, su / sw)), std::min(1.0, std::max(0.0, sv / sw))};
  return true;
}

bool uses_global_search(const ChromaSettings& settings) {
  return settings.search == ChromaSettings::Search::global &&
         (settings.solver == nullptr || settings.solver == &procrustes_solver());
}

ChromaFit fit_chroma(const ChromaPoints& points, Mode mode, const ShapeSet& shapes, const ChromaSettings& settings,
                     std::uint64_t block_seed, const ChromaLogTargets* log_targets, ShapeSolveCache* cache,
                     ChromaWorkspace* workspace) {
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

  if (uses_global_search(settings))
    return fit_chroma_global(points, mode, shapes, settings, log_targets, cache, workspace);

  std::vector<ShapeFitProblem> problems;
  problems.reserve(kShapeCount);
  std::array<ShapeSolve, kShapeCount> solves{};
  const bool cached = cache != nullptr && cache->valid && cache->mode == mode;
  for (int s = 0; s < kShapeCount; ++s) {
    problems.push_back(make_shape_fit_problem(
        chroma_fit_data(points, mode, shapes.shapes[static_cast<std::size_t>(s)], settings, nullptr)));
    if (cached) continue;   // the same problems were solved for another mode of this block
    const std::uint64_t seed = derive_stream_seed(block_seed, static_cast<std::uint64_t>(static_cast<int>(mode) * kShapeCount + s));
    solves[static_cast<std::size_t>(s)] = solve_shape(problems.back(), settings, seed, workspace);
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
    const std::array<double, kBaseCoordinateCount> x = base_lattice_point(log_problems.back(), solves[ss].base);
    rank_error[ss] = log_problems.back().eval(x.data());
  }
  std::array<int, kShapeCount> order{};
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return rank_error[static_cast<std::size_t>(a)] < rank_error[static_cast<std::size_t>(b)];
  });
  const int candidates =
      settings.polish_candidates == 0 ? kShapeCount : std::min(kShapeCount, settings.polish_candidates);
  int best = -1;
  double best_error = 0.0;
  ShapeSolve best_solve;
  for (int r = 0; r < candidates; ++r) {
    const std::size_t s = static_cast<std::size_t>(order[static_cast<std::size_t>(r)]);
    ShapeSolve solve = solves[s];
    double error = solve.error;
    if (log_polish) {
      error = rank_error[s];
      if (settings.polish && polish_log_base_colours(log_problems[s].error(), settings, &solve.base, &error))
        solve.error = problems[s].eval(base_lattice_point(problems[s], solve.base).data());
    } else if (settings.polish && !solve.proven_optimal) {
      // A proven lattice optimum of the fit error (interval_bb, exhaustive run to the end) cannot be polished in that
      // error; a capped or local answer can.
      polish_base_colours(problems[s], settings, &solve.base, &solve.error);
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
  if (settings.fit_indices)
    fit.index = assign_chroma_indices(points, mode, shapes.shapes[static_cast<std::size_t>(best)], fit.base, settings);
  return fit;
}

}  // namespace blocklab::munkberg
