// The global chroma search of the `munkberg` format (formats/munkberg/munkberg_chroma.h, ChromaSettings::Search::
// global; Munkberg et al. 2008 section 7.1): "The error is evaluated for the best fit of each template shape, and we
// select the shape with the smallest overall error", with the work spent where it pays:
//   1. the block's chroma points (group means for shape II) are clustered ONCE and every (shape, cluster level,
//      landmark correspondence) Procrustes candidate of the 8 shapes is ranked by its bound (Procrustes functional +
//      scatter), formats/munkberg/shape_fit/procrustes_templates.h; the best `search_candidates` (+ ties) are kept and
// the
//      best `search_refined` of them refined clamp-aware in the fit error (linear or section 7.2's stretched);
//   2. each kept candidate is snapped to the 7-bit lattice and evaluated in the polish error (log2rgb: the block's
//      reconstruction error, munkberg_log_error.h; fit: the shape-fit error); each shape keeps its best (log2rgb:
//      exactly only while it could still be among the `polish_candidates` best shapes);
//   3. the shapes are ranked by that error and the best `polish_candidates` get the lattice polish (section 7.1);
//      the lowest error wins (ties: the shape ranked first, then the lower shape index).
// Compared with the per-shape search (16 independent procrustes solves per block, each clustering the same points
// and refining 12 candidates): one clustering per mode, ~8 refinements instead of ~96, and no stretched-error
// evaluation of candidates whose reconstruction error is evaluated anyway. docs/benchmarks-munkberg.md has the
// measured time and quality of both.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <optional>

#include "core/error.h"
#include "formats/munkberg/munkberg_base_colour_sums.h"
#include "formats/munkberg/munkberg_chroma.h"

namespace blocklab::munkberg {

ChromaFit fit_chroma_global(const ChromaPoints& points, Mode mode, const ShapeSet& shapes,
                            const ChromaSettings& settings, const ChromaLogTargets* log_targets,
                            ShapeSolveCache* cache, ChromaWorkspace* workspace) {
  // A search given no workspace makes its own.
  const std::unique_ptr<ChromaWorkspace> own = workspace == nullptr ? std::make_unique<ChromaWorkspace>() : nullptr;
  ChromaWorkspace& w = workspace != nullptr ? *workspace : *own;
  const bool log_polish = settings.polish_error == ChromaSettings::PolishError::log2rgb;
  if (log_polish && log_targets == nullptr) fail("munkberg", "internal: log2rgb polish without decoded luminance");
  const ShapeFitData data = chroma_fit_data(points, mode, shapes.shapes[0], settings, nullptr);

  // Constant chroma (option skip_constant): every Procrustes candidate of a block whose weighted points coincide is
  // the scale-0 transform at that point (both base points on it), so its ranking is skipped (closed form below).
  Point2 constant_point;
  const bool constant = settings.skip_constant && constant_chroma(data, settings.constant_tolerance, &constant_point);

  // 1. Ranked candidates of all shapes (cached per points: shape I and two_plane share them).
  std::vector<TemplateCandidate> ranked_local;
  const std::vector<TemplateCandidate>* ranked = &ranked_local;
  if (constant) {
    // Nothing to rank (step 2 gives every shape the closed-form answer).
  } else if (cache != nullptr && cache->valid && cache->mode == mode) {
    ranked = &cache->ranked;
  } else {
    TemplateRankingOptions options;
    options.procrustes = settings.procrustes_options ? *settings.procrustes_options
                                                     : procrustes_options_of(settings.solver_options);
    options.kept = settings.search_candidates;
    options.tie_limit = settings.search_tie_limit;
    options.per_template = settings.search_per_shape;
    options.refined = settings.search_refined;
    options.exponent = settings.error_kind == ShapeErrorKind::stretched ? settings.alpha : 1.0;
    std::vector<ShapeTemplate>& templates = w.templates;   // the worker's (one ranking per block and mode)
    templates.assign(shapes.shapes.begin(), shapes.shapes.end());
    ranked_local = rank_template_candidates(data.points, data.weights, templates, options, &w.ranking);
    if (cache != nullptr) {
      cache->valid = true;
      cache->mode = mode;
      cache->ranked = std::move(ranked_local);
      ranked = &cache->ranked;
    }
  }

  // 2. Snap and evaluate each candidate in the polish error; each shape keeps its best (strict: first of equals).
  // Each shape's error, built on first use: the log2[RGB] reconstruction error or the shape-fit problem.
  // The log2[RGB] error differs between shapes only in its template: one error (targets and offsets computed once)
  // whose shape is set per use.
  std::optional<ChromaLogError> log_error;
  std::array<std::unique_ptr<ShapeFitProblem>, kShapeCount> fit_problems;
  const auto log_error_of = [&](int s) -> const ChromaLogError& {
    const ShapeTemplate& shape = shapes.shapes[static_cast<std::size_t>(s)];
    if (!log_error) log_error = ChromaLogError::make(mode, shape, *log_targets);
    log_error->shape = shape;
    return *log_error;
  };
  const auto fit_problem_of = [&](int s) -> const ShapeFitProblem& {
    std::unique_ptr<ShapeFitProblem>& slot = fit_problems[static_cast<std::size_t>(s)];
    if (!slot)
      slot = std::make_unique<ShapeFitProblem>(make_shape_fit_problem(
          chroma_fit_data(points, mode, shapes.shapes[static_cast<std::size_t>(s)], settings, nullptr)));
    return *slot;
  };
  // The error at codes; with the log2rgb error only exact below `bound` (eval_below: enough to compare with it).
  // The base colours' error shares, shared by every shape's candidates and polish (munkberg_base_colour_sums.h).
  // The worker's, emptied per use: the table is ~35 KB, allocated once per worker instead of once per block and mode.
  BaseColourSums* const base_sums = log_polish ? &w.base_sums : nullptr;
  if (base_sums != nullptr) base_sums->clear();
  const auto error_at = [&](int s, const std::array<int, kBaseCoordinateCount>& codes, double bound) {
    return log_polish ? eval_below_cached(log_error_of(s), codes, bound, base_sums)
                      : fit_problem_of(s).eval(base_code_point(codes).data());
  };
  constexpr double kNoBound = std::numeric_limits<double>::infinity();
  std::array<bool, kShapeCount> have{};
  std::array<double, kShapeCount> shape_error{};
  std::array<std::array<int, kBaseCoordinateCount>, kShapeCount> shape_codes{};
  // Codes already evaluated per shape (up to kRemembered each): different candidates often snap to the same codes,
  // and a repeat has the error of its first evaluation, which is >= the shape's best since then, so it can never
  // replace it (strict comparison below).
  constexpr int kRemembered = 32;
  std::array<std::array<std::array<int, kBaseCoordinateCount>, kRemembered>, kShapeCount> evaluated;
  std::array<int, kShapeCount> evaluated_count{};
  // Only the `polish_candidates` best shapes (k) are used in step 3, so a candidate's error is needed exactly only
  // when it could bring its shape into the top k: at or below the k-th smallest error recorded so far (equal: the
  // lower shape index may win the tie, hence the next double up as the bound). A shape whose own recorded error is
  // among the k smallest has a lower bound of its own already. The evaluation stops at that bound. Exact: the k best
  // shapes get the same errors and codes as with each shape's own bound alone. A shape s of the true top k has at
  // most k - 1 shapes ahead of it, so when its best candidate is evaluated the k-th smallest recorded error (which
  // only decreases) is >= its error, and its own earlier record is above it: the value is exact. Any other shape
  // records a value >= its true best, which keeps it behind the top k.
  const int top = settings.polish_candidates;
  const bool use_top_bound = log_polish && top > 0 && settings.top_shape_bound;
  double top_bound = kNoBound;   // recomputed whenever a recorded error changes
  const auto update_top_bound = [&] {
    std::array<double, kShapeCount> recorded{};
    int count = 0;
    for (std::size_t t = 0; t < kShapeCount; ++t)
      if (have[t]) recorded[static_cast<std::size_t>(count++)] = shape_error[t];
    if (count < top) return;
    std::nth_element(recorded.begin(), recorded.begin() + (top - 1), recorded.begin() + count);
    top_bound = std::nextafter(recorded[static_cast<std::size_t>(top - 1)], kNoBound);
  };
  for (const TemplateCandidate& entry : *ranked) {
    if (entry.candidate.duplicate) continue;   // refined onto an earlier candidate's assignment
    const std::size_t s = static_cast<std::size_t>(entry.shape);
    const std::array<int, kBaseCoordinateCount> codes = snap_base_codes(entry.candidate.base0, entry.candidate.base1);
    const auto remembered = evaluated[s].begin() + evaluated_count[s];
    if (std::find(evaluated[s].begin(), remembered, codes) != remembered) continue;
    if (evaluated_count[s] < kRemembered) evaluated[s][static_cast<std::size_t>(evaluated_count[s]++)] = codes;
    const double error = error_at(entry.shape, codes, std::min(have[s] ? shape_error[s] : kNoBound, top_bound));
    if (!(error == error)) continue;   // NaN: never an answer
    if (!have[s] || error < shape_error[s]) {
      have[s] = true;
      shape_error[s] = error;
      shape_codes[s] = codes;
      if (use_top_bound) update_top_bound();
    }
  }
  if (constant) {
    // Base points both on the point: all four landmarks decode to the same lattice point for EVERY shape, so every
    // shape has the same error (evaluated once) and step 3's stable ranking polishes shapes 0, 1, ... in order:
    // what the ranked search gives when all its candidates snap to these codes.
    const std::array<int, kBaseCoordinateCount> codes = snap_base_codes(constant_point, constant_point);
    const double error = error_at(0, codes, kNoBound);
    have.fill(true);
    shape_error.fill(error);
    shape_codes.fill(codes);
  }
  // Every candidate NaN or duplicate (cannot happen for finite points: the first refined one is never a duplicate):
  // the lattice centre on shape 0.
  if (std::none_of(have.begin(), have.end(), [](bool h) { return h; })) {
    have[0] = true;
    shape_codes[0].fill(kBaseCoordinateMax / 2);
    shape_error[0] = error_at(0, shape_codes[0], kNoBound);
  }

  // 3. Rank the shapes that have an answer (stable: equal errors keep the lower shape index), polish the best.
  std::array<int, kShapeCount> order{};
  std::iota(order.begin(), order.end(), 0);
  const auto end = std::stable_partition(order.begin(), order.end(), [&](int s) { return have[static_cast<std::size_t>(s)]; });
  std::stable_sort(order.begin(), end, [&](int a, int b) {
    return shape_error[static_cast<std::size_t>(a)] < shape_error[static_cast<std::size_t>(b)];
  });
  const int available = static_cast<int>(end - order.begin());
  const int candidates = settings.polish_candidates == 0 ? available : std::min(available, settings.polish_candidates);
  int best = -1;
  double best_error = 0.0;
  std::array<int, kBaseCoordinateCount> best_codes{};
  const double first_error = shape_error[static_cast<std::size_t>(order[0])];
  // good_enough compares the block error, which is the log2rgb polish error plus the constant error of the texels that
  // decode to true black (left out of ChromaLogError).
  const bool good_enough = log_polish && settings.good_enough > 0.0;
  const double black_error = good_enough ? log_targets->black_texels_error() : 0.0;
  for (int r = 0; r < candidates; ++r) {
    const int s = order[static_cast<std::size_t>(r)];
    std::array<int, kBaseCoordinateCount> codes = shape_codes[static_cast<std::size_t>(s)];
    double error = shape_error[static_cast<std::size_t>(s)];
    // polish_margin (a speed / quality trade, off by default): a lower-ranked shape whose unpolished error is more
    // than (1 + margin) times the first one's is not polished (nor considered).
    if (r > 0 && settings.polish_margin > 0.0 && error > (1.0 + settings.polish_margin) * first_error) break;
    // good_enough (approximate, off at 0; a limit on the block error): stop once a shape is good enough; a shape
    // already that good is kept unpolished.
    if (r > 0 && good_enough && best_error + black_error <= settings.good_enough) break;
    if (settings.polish && !(good_enough && error + black_error <= settings.good_enough)) {
      if (log_polish) {
        polish_log_base_colours(log_error_of(s), settings, &codes, &error, base_sums);
      } else {
        polish_base_colours(fit_problem_of(s), settings, &codes, &error);
      }
    }
    // Strict: ties keep the candidate ranked first.
    if (best < 0 || error < best_error) {
      best = s;
      best_error = error;
      best_codes = codes;
    }
  }

  ChromaFit fit;
  fit.shape = best;
  fit.base = best_codes;
  fit.polish_error = best_error;
  fit.fit_error = log_polish ? 0.0 : best_error;
  if (settings.fit_indices)
    fit.index = assign_chroma_indices(points, mode, shapes.shapes[static_cast<std::size_t>(best)], fit.base, settings);
  return fit;
}

}  // namespace blocklab::munkberg
