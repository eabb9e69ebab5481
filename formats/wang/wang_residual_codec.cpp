// The residual 1D codec of the `wang` format (formats/wang/wang_residual_codec.h).
#include "formats/wang/wang_residual_codec.h"

#include <algorithm>
#include <cmath>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "formats/common/s3tc_color_fit.h"
#include "formats/wang/wang_zone_encoding.h"

namespace blocklab {
namespace wang {

namespace {

using Endpoints = std::array<std::array<int, 3>, 2>;

// The 4 palette entries' 1D values: fetched 8-bit colours (round to nearest, never a tie) dotted with the ranges;
// the arithmetic of ResidualBlockError<double> at a lattice point.
void entry_values(const ResidualBlockError& error, const Endpoints& endpoints, double entries[4]) {
  int expanded[2][3];
  for (int e = 0; e < 2; ++e)
    for (int channel = 0; channel < 3; ++channel)
      expanded[e][channel] = expand_565_channel(endpoints[e][channel], channel);
  for (int k = 0; k < 4; ++k) {
    const PaletteWeights w = bc1_palette_weights(Bc1Mode::four_color, k);
    double fetched[3];
    for (int channel = 0; channel < 3; ++channel) {
      const int numerator = w.w0 * expanded[0][channel] + w.w1 * expanded[1][channel];
      fetched[channel] = static_cast<double>((2 * numerator + w.d) / (2 * w.d)) / 255.0;
    }
    entries[k] = (fetched[0] * error.ranges[0] + fetched[1] * error.ranges[1]) + fetched[2] * error.ranges[2] +
                 error.rmin;
  }
}

#if defined(__SSE2__)
// evaluate() without codes: the four entries' texel errors two per SSE2 register, each lane the same IEEE
// operations as texel_error(L, reconstruct(L_a, entry)) (maxpd / minpd equal max / min on these finite values), the
// minimum across the lanes, and the texels summed in order 0..15: the same double as the scalar loop.
double total_of_best_entries(const ResidualBlockError& error, const double entries[4]) {
  const __m128d zero = _mm_setzero_pd(), sign = _mm_set1_pd(-0.0), c = _mm_set1_pd(error.c);
  const __m128d entries_low = _mm_loadu_pd(&entries[0]), entries_high = _mm_loadu_pd(&entries[2]);
  double total = 0.0;
  for (int texel = 0; texel < 16; ++texel) {
    const __m128d target = _mm_set1_pd(error.luminance[texel]), base = _mm_set1_pd(error.decoded[texel]);
    __m128d errors[2];
    for (int half = 0; half < 2; ++half) {
      const __m128d entry = half == 0 ? entries_low : entries_high;
      const __m128d decoded = error.ratio ? _mm_add_pd(base, _mm_mul_pd(base, entry)) : _mm_add_pd(base, entry);
      const __m128d shown = _mm_max_pd(decoded, zero);
      errors[half] = _mm_div_pd(_mm_andnot_pd(sign, _mm_sub_pd(target, shown)), _mm_add_pd(_mm_min_pd(target, shown), c));
    }
    const __m128d pair = _mm_min_pd(errors[0], errors[1]);
    total += _mm_cvtsd_f64(_mm_min_sd(pair, _mm_unpackhi_pd(pair, pair)));
  }
  return total;
}
#endif

double evaluate(const ResidualBlockError& error, const Endpoints& endpoints, std::uint8_t* codes) {
  double entries[4];
  entry_values(error, endpoints, entries);
#if defined(__SSE2__)
  if (codes == nullptr) return total_of_best_entries(error, entries);
#endif
  double total = 0.0;
  for (int texel = 0; texel < 16; ++texel) {
    double best = std::numeric_limits<double>::infinity();
    int best_code = 0;
    for (int k = 0; k < 4; ++k) {
      const double distance =
          error.texel_error(error.luminance[texel], error.reconstruct(error.decoded[texel], entries[k]));
      if (distance < best) {
        best = distance;
        best_code = k;
      }
    }
    total += best;
    if (codes) codes[texel] = static_cast<std::uint8_t>(best_code);
  }
  return total;
}

// The residual each texel needs (S = L - L_a, or T = S / L_a; T = 0 where L_a <= 0) and its weight in that domain.
void residual_targets_of(const ResidualBlockError& error, double residual[16], double weight[16]) {
  for (int texel = 0; texel < 16; ++texel) {
    const double base = error.decoded[texel];
    const double s = error.luminance[texel] - base;
    if (!error.ratio) {
      residual[texel] = s;
      weight[texel] = error.weight[texel];
    } else {
      residual[texel] = base > 0.0 ? s / base : 0.0;
      weight[texel] = error.weight[texel] * std::max(base, 0.0);
    }
  }
}

// Weighted Lloyd rounds for the 1D palette {s0, s1, (2 s0 + s1) / 3, (s0 + 2 s1) / 3}.
std::pair<double, double> fit_1d_endpoints(const double residual[16], const double weight[16], int rounds) {
  double s0 = residual[0], s1 = residual[0];
  for (int texel = 1; texel < 16; ++texel) {
    s0 = std::min(s0, residual[texel]);
    s1 = std::max(s1, residual[texel]);
  }
  static constexpr double kFraction[4] = {0.0, 1.0, 1.0 / 3.0, 2.0 / 3.0};
  for (int round = 0; round < rounds; ++round) {
    double aa = 0.0, ab = 0.0, bb = 0.0, ax = 0.0, bx = 0.0;
    for (int texel = 0; texel < 16; ++texel) {
      int best = 0;
      double best_distance = std::numeric_limits<double>::infinity();
      for (int k = 0; k < 4; ++k) {
        const double distance = std::abs(residual[texel] - ((1.0 - kFraction[k]) * s0 + kFraction[k] * s1));
        if (distance < best_distance) {
          best_distance = distance;
          best = k;
        }
      }
      const double b = kFraction[best], a = 1.0 - b, w = weight[texel];
      aa += w * a * a;
      ab += w * a * b;
      bb += w * b * b;
      ax += w * a * residual[texel];
      bx += w * b * residual[texel];
    }
    const double determinant = aa * bb - ab * ab;
    if (!(std::abs(determinant) > 1e-300 * (aa * bb + 1e-300))) break;
    const double next0 = (ax * bb - bx * ab) / determinant;
    const double next1 = (aa * bx - ab * ax) / determinant;
    if (!std::isfinite(next0) || !std::isfinite(next1)) break;
    s0 = next0;
    s1 = next1;
  }
  return {s0, s1};
}

// The `count` table colours whose values are nearest to `target` (ties to the lower table position).
std::vector<std::uint16_t> nearest_colours(const ResidualTable& table, double target, int count) {
  const auto& sorted = table.sorted;
  std::size_t right = static_cast<std::size_t>(
      std::lower_bound(sorted.begin(), sorted.end(), std::make_pair(target, std::uint16_t{0})) - sorted.begin());
  std::size_t left = right;   // candidates are [left, right) grown outwards
  std::vector<std::uint16_t> out;
  while (static_cast<int>(out.size()) < count && (left > 0 || right < sorted.size())) {
    const bool take_left =
        right >= sorted.size() || (left > 0 && target - sorted[left - 1].first <= sorted[right].first - target);
    if (take_left) out.push_back(sorted[--left].second);
    else out.push_back(sorted[right++].second);
  }
  return out;
}

Endpoints endpoints_of(std::uint16_t word0, std::uint16_t word1) {
  return {unpack_rgb565(word0), unpack_rgb565(word1)};
}

ResidualFit finish(const ResidualBlockError& error, const Endpoints& endpoints) {
  Bc1Params color;
  color.endpoints = endpoints;
  color.mode = Bc1Mode::four_color;
  ResidualFit fit;
  fit.error = evaluate(error, endpoints, color.indices.data());
  fit.color = canonicalise_bc3_color(color);
  return fit;
}

}  // namespace

ResidualTable build_residual_table(const ResidualBlockError& error) {
  ResidualTable table;
  table.sorted.reserve(65536);
  for (unsigned word = 0; word < 65536u; ++word) {
    const std::array<int, 3> c = unpack_rgb565(word);
    double fetched[3];
    for (int channel = 0; channel < 3; ++channel)
      fetched[channel] = static_cast<double>(expand_565_channel(c[channel], channel)) / 255.0;
    const double value =
        (fetched[0] * error.ranges[0] + fetched[1] * error.ranges[1]) + fetched[2] * error.ranges[2] + error.rmin;
    table.sorted.emplace_back(value, static_cast<std::uint16_t>(word));
  }
  std::sort(table.sorted.begin(), table.sorted.end());
  return table;
}

void residual_entries(const ResidualBlockError& error, const Bc1Params& color, double entries[4]) {
  entry_values(error, color.endpoints, entries);
}

double residual_error_with_codes(const ResidualBlockError& error, const Bc1Params& color) {
  double entries[4];
  entry_values(error, color.endpoints, entries);
  double total = 0.0;
  for (int texel = 0; texel < 16; ++texel) {
    const double decoded = error.reconstruct(error.decoded[texel], entries[color.indices[texel] & 3]);
    total += error.texel_error(error.luminance[texel], decoded);
  }
  return total;
}

ResidualFit fit_residual_block(const ResidualBlockError& error, const ResidualTable& table, const Zones& zones,
                               const SearchEffort& effort, Codec codec, const BlockSolverSetup& solver,
                               std::size_t block_index) {
  double residual[16], weight[16];
  residual_targets_of(error, residual, weight);
  if (codec == Codec::bc3) {
    ColorBlock block;
    for (int texel = 0; texel < 16; ++texel) {
      const std::array<double, 3> rgb = residual_targets(residual[texel], zones);
      for (int channel = 0; channel < 3; ++channel)
        block.texels[texel][channel] = static_cast<float>(rgb[channel] * 255.0);
    }
    block.weights[0] = block.weights[1] = block.weights[2] = 1.0f;
    ColorFitSettings settings;
    settings.search = effort.s3tc;
    settings.allow_three_color = false;
    ResidualFit fit;
    fit.color = fit_color_block(block, settings);
    fit.error = residual_error_with_codes(error, fit.color);
    return fit;
  }

  const std::pair<double, double> ends = fit_1d_endpoints(residual, weight, effort.residual_rounds);
  const int count = solver.builtin() ? effort.residual_candidates : 1;
  const std::vector<std::uint16_t> first = nearest_colours(table, ends.first, count);
  const std::vector<std::uint16_t> second = nearest_colours(table, ends.second, count);
  Endpoints best = endpoints_of(first.front(), second.front());
  double best_error = evaluate(error, best, nullptr);
  for (const std::uint16_t a : first)
    for (const std::uint16_t b : second) {
      const Endpoints candidate = endpoints_of(a, b);
      const double candidate_error = evaluate(error, candidate, nullptr);
      if (candidate_error < best_error) {
        best_error = candidate_error;
        best = candidate;
      }
    }
  if (!solver.builtin()) {
    ResidualBlockError problem_error = error;
    problem_error.texture_unit = true;
    const auto problem = make_residual_block_problem(problem_error);
    std::vector<double> x0;
    for (const auto& endpoint : best)
      for (const int value : endpoint) x0.push_back(value);
    const std::vector<std::int64_t> answer = solve_block_on_lattice(solver, problem, x0, block_index);
    for (int k = 0; k < 6; ++k) best[k / 3][k % 3] = static_cast<int>(answer[k]);
  }
  return finish(error, best);
}

}  // namespace wang
}  // namespace blocklab
