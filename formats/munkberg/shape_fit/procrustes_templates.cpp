// Multi-template Procrustes candidates from one clustering (formats/munkberg/shape_fit/procrustes_templates.h; Munkberg
// et al. 2008 section 7.1, eqs. 12-15).
#include "formats/munkberg/shape_fit/procrustes_templates.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "core/error.h"
#include "solvers/procrustes/level_candidates.h"
#include "solvers/procrustes/weighted_procrustes.h"

namespace blocklab {

namespace {

constexpr const char* kName = "procrustes templates";

}  // namespace

std::vector<TemplateCandidate> rank_template_candidates(const std::vector<Point2>& points,
                                                        const std::vector<double>& weights,
                                                        const std::vector<ShapeTemplate>& shapes,
                                                        const TemplateRankingOptions& options,
                                                        TemplateRankingWorkspace* workspace) {
  require_valid_options(kName, options.procrustes);
  if (points.empty() || weights.size() != points.size())
    fail(kName, "the point set needs at least one point and one weight per point");
  if (shapes.empty()) fail(kName, "no template shape");
  if (options.kept < 1 || options.tie_limit < 0 || options.refined < 0 || options.per_template < 0)
    fail(kName, "kept must be >= 1, tie_limit, per_template and refined >= 0");

  std::optional<TemplateRankingWorkspace> own_workspace;   // made only when the caller gives none
  if (workspace == nullptr) own_workspace.emplace();
  TemplateRankingWorkspace& w = workspace != nullptr ? *workspace : *own_workspace;
  std::vector<PointClustering>& levels = w.levels;
  procrustes_cluster_levels(points, weights, options.procrustes, levels);
  const int top_level = static_cast<int>(levels.size());
  const int bottom_level = std::min(options.procrustes.min_clusters, top_level);

  // Every candidate, in enumeration order; its index is the tie-break that makes the ranking a strict order. The
  // buffers here and below are the workspace's (this runs once per block and mode): with a workspace reused across
  // blocks, only the returned ranking allocates.
  using Key = CandidateKey;
  // The hot ones are moved into locals for the call and back at its end (their storage is kept): locals cannot
  // alias each other, so the enumeration loop keeps their ends in registers (measured: ~6 % of this function).
  std::vector<TemplateCandidate> all = std::move(w.all);
  std::vector<Key> keys = std::move(w.keys);
  std::vector<char>& chosen_flag = w.chosen_flag;
  std::vector<ProcrustesCandidate> level_candidates = std::move(w.level_candidates);
  all.clear();
  keys.clear();
  for (int level = top_level; level >= bottom_level; --level) {
    const PointClustering& clustering = levels[static_cast<std::size_t>(level - 1)];
    // k = 1: the same transform (scale 0 at the centre) for every template; listed once, for template 0.
    const std::size_t template_count = level == 1 ? 1 : shapes.size();
    // One set of targets and (closed form) one fitter per level serve every template.
    const LevelTargets targets(clustering);
    std::optional<SimilarityFitter> fitter;
    if (options.procrustes.svd != ProcrustesMethod::eigen_svd) fitter = targets.fitter();
    for (std::size_t t = 0; t < template_count; ++t) {
      level_candidates.clear();
      append_level_candidates(clustering, targets, fitter ? &*fitter : nullptr, shapes[t].coefficients(),
                              options.procrustes.svd, &level_candidates);
      for (const ProcrustesCandidate& candidate : level_candidates) {
        if (std::isnan(candidate.error_bound)) continue;   // NaN bounds never rank (finite points give none)
        keys.push_back({candidate.error_bound, all.size()});
        all.push_back(TemplateCandidate{static_cast<int>(t), candidate});
      }
    }
  }
  const auto before = [](const Key& a, const Key& b) {
    return a.bound < b.bound || (a.bound == b.bound && a.index < b.index);
  };
  // The best kept + tie_limit in order, then cut after `kept` plus the ties with the last kept one.
  const std::size_t head = std::min(keys.size(), static_cast<std::size_t>(options.kept) +
                                                     static_cast<std::size_t>(options.tie_limit));
  if (head < keys.size())
    std::nth_element(keys.begin(), keys.begin() + static_cast<std::ptrdiff_t>(head), keys.end(), before);
  std::sort(keys.begin(), keys.begin() + static_cast<std::ptrdiff_t>(head), before);
  std::size_t kept = std::min(head, static_cast<std::size_t>(options.kept));
  if (kept > 0) {
    const double last = keys[kept - 1].bound;
    while (kept < head && procrustes_bound_ties(keys[kept].bound, last)) ++kept;
  }
  std::vector<Key>& chosen = w.chosen;
  chosen.assign(keys.begin(), keys.begin() + static_cast<std::ptrdiff_t>(kept));
  // Each template's best `per_template` among the others: one scan with a small sorted list per template.
  if (options.per_template > 0) {
    chosen_flag.assign(all.size(), 0);
    for (const Key& k : chosen) chosen_flag[k.index] = 1;
    const std::size_t limit = static_cast<std::size_t>(options.per_template);
    std::vector<std::size_t>& count = w.count;
    count.assign(shapes.size(), 0);
    for (const Key& k : chosen) ++count[static_cast<std::size_t>(all[k.index].shape)];
    std::vector<std::vector<Key>>& best = w.best;
    best.resize(shapes.size());
    for (std::vector<Key>& list : best) list.clear();
    for (std::size_t i = 0; i < all.size(); ++i) {
      if (chosen_flag[i]) continue;
      const std::size_t t = static_cast<std::size_t>(all[i].shape);
      if (count[t] >= limit) continue;   // already represented among the kept ones
      const Key key{all[i].candidate.error_bound, i};
      std::vector<Key>& list = best[t];
      const std::size_t room = limit - count[t];
      if (list.size() == room && !before(key, list.back())) continue;
      std::size_t j = list.size();
      while (j > 0 && before(key, list[j - 1])) --j;
      list.insert(list.begin() + static_cast<std::ptrdiff_t>(j), key);
      if (list.size() > room) list.pop_back();
    }
    for (std::size_t t = 0; t < shapes.size(); ++t) chosen.insert(chosen.end(), best[t].begin(), best[t].end());
    std::sort(chosen.begin(), chosen.end(), before);
  }
  std::vector<TemplateCandidate> ranked;
  ranked.reserve(chosen.size());
  for (const Key& k : chosen) ranked.push_back(all[k.index]);

  // Clamp-aware refinement of the best `refined`, each on its own template; duplicates are per template.
  const std::size_t refined = std::min(ranked.size(), static_cast<std::size_t>(options.refined));
  if (refined > 0 && options.procrustes.refine_iterations > 0) {
    const RefineMeasure measure(options.exponent);
    std::vector<double>& targets = w.refinement.targets;
    targets.resize(2 * points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      targets[i] = measure.map(points[i].u);
      targets[points.size() + i] = measure.map(points[i].v);
    }
    std::vector<std::vector<std::uint64_t>>& seen = w.seen;
    seen.resize(shapes.size());
    for (std::vector<std::uint64_t>& list : seen) list.clear();
    std::vector<int>& nearest = w.refinement.nearest;
    std::vector<int>& next_nearest = w.refinement.next_nearest;
    nearest.resize(points.size());
    next_nearest.resize(points.size());
    for (std::size_t i = 0; i < refined; ++i) {
      TemplateCandidate& entry = ranked[i];
      const std::size_t t = static_cast<std::size_t>(entry.shape);
      entry.candidate = refine_procrustes_candidate(targets, weights, measure, shapes[t], entry.candidate,
                                                    options.procrustes.refine_iterations, seen[t], nearest,
                                                    next_nearest);
    }
  }
  w.all = std::move(all);
  w.keys = std::move(keys);
  w.level_candidates = std::move(level_candidates);
  return ranked;
}

}  // namespace blocklab
