// The luminance 1D codec of the `wang` format (formats/wang/wang_luminance_codec.h).
#include "formats/wang/wang_luminance_codec.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <limits>
#include <vector>

#include "formats/bc4/bc4_encoder.h"
#include "formats/wang/wang_trial_error.h"
#include "formats/wang/wang_zone_encoding.h"

namespace blocklab {
namespace wang {

namespace {

// The 8 fetched values of an alpha palette as 8-bit integers (round to nearest, never a tie for BC3): the
// interpolants ((d - k) e0 + k e1) / d of codes 2.. rounded as (2 n + d) / (2 d), with the divisors spelled out as
// constants (14 and 10) so that the compiler divides by multiplication.
void fetched_alpha_codes(int e0, int e1, Bc4Mode mode, int out[8]) {
  out[0] = e0;
  out[1] = e1;
  if (mode == Bc4Mode::eight_value) {
    for (int k = 1; k <= 6; ++k) out[k + 1] = (2 * ((7 - k) * e0 + k * e1) + 7) / 14;
  } else {
    for (int k = 1; k <= 4; ++k) out[k + 1] = (2 * ((5 - k) * e0 + k * e1) + 5) / 10;
    out[6] = 0;     // the 6-value mode's constants
    out[7] = 255;
  }
}

// code / 255 for every 8-bit code, the same double as the division it replaces.
const double* code_fractions() {
  static const std::array<double, 256> table = [] {
    std::array<double, 256> fractions{};
    for (int code = 0; code < 256; ++code) fractions[static_cast<std::size_t>(code)] = static_cast<double>(code) / 255.0;
    return fractions;
  }();
  return table.data();
}

struct Candidate {
  int endpoints[4] = {0, 0, 0, 0};   // tex0 e0, e1, tex1 e0, e1
  Bc4Mode modes[2] = {Bc4Mode::eight_value, Bc4Mode::eight_value};
};

// The distinct eq. 4 terms of one alpha channel of a candidate (a constant channel has one or three), each with its
// lowest code: channel 0 gives fetched * high, channel 1 fetched * low + tmin.
struct ChannelParts {
  double value[8];
  int code[8];
  int count = 0;
};

ChannelParts channel_parts(const LuminanceBlockError& error, const Candidate& candidate, int channel) {
  int q[8];
  fetched_alpha_codes(candidate.endpoints[2 * channel], candidate.endpoints[2 * channel + 1], candidate.modes[channel],
                      q);
  // A code is left out when an earlier code has its value. The interpolants run monotonically from e0 to e1 (the
  // chain e0, code 2, ..., e1), so equal values sit next to each other on it: code k >= 2 repeats an earlier one
  // exactly when it equals its chain predecessor (code 0 for code 2) or e1 (code 1); the 6-value constants 0 and
  // 255 repeat one exactly when the chain's low or high end is 0 or 255.
  const int last_interpolant = candidate.modes[channel] == Bc4Mode::eight_value ? 7 : 5;
  bool repeated[8];
  repeated[0] = false;
  repeated[1] = q[1] == q[0];
  for (int k = 2; k <= last_interpolant; ++k) repeated[k] = q[k] == q[k == 2 ? 0 : k - 1] || q[k] == q[1];
  if (last_interpolant == 5) {
    repeated[6] = std::min(q[0], q[1]) == 0;
    repeated[7] = std::max(q[0], q[1]) == 255;
  }
  const double* fractions = code_fractions();
  ChannelParts parts;
  for (int k = 0; k < 8; ++k) {
    if (repeated[k]) continue;
    parts.value[parts.count] = channel == 0 ? fractions[q[k]] * error.high : fractions[q[k]] * error.low + error.tmin;
    parts.code[parts.count++] = k;
  }
  return parts;
}

// The error with each texel's best pair of codes (written to codes0 / codes1 when not null); the arithmetic of
// LuminanceBlockError<double> at a lattice point. Without codes, nearest_sum_total_below gives the same total (or,
// at or above `bound`, a value that is also at or above it).
double evaluate(const TrialTexels& texels, const ChannelParts& parts0, const ChannelParts& parts1,
                std::uint8_t* codes0, std::uint8_t* codes1,
                double bound = std::numeric_limits<double>::infinity()) {
  if (!codes0 && !codes1)
    return nearest_sum_total_below(texels, parts0.value, parts0.count, parts1.value, parts1.count, bound);
  int first[16], second[16];
  const double total = nearest_sum_total_with_choice(texels, parts0.value, parts0.count, parts1.value, parts1.count,
                                                     first, second);
  for (int texel = 0; texel < 16; ++texel) {
    if (codes0) codes0[texel] = static_cast<std::uint8_t>(parts0.code[first[texel]]);
    if (codes1) codes1[texel] = static_cast<std::uint8_t>(parts1.code[second[texel]]);
  }
  return total;
}

double evaluate(const TrialTexels& texels, const Candidate& candidate, std::uint8_t* codes0, std::uint8_t* codes1) {
  const LuminanceBlockError& error = *texels.error;
  return evaluate(texels, channel_parts(error, candidate, 0), channel_parts(error, candidate, 1), codes0, codes1);
}

// The four endpoints as one key (the modes are fixed during a descent).
std::uint32_t endpoint_key(const Candidate& candidate) {
  return static_cast<std::uint32_t>(candidate.endpoints[0]) | static_cast<std::uint32_t>(candidate.endpoints[1]) << 8 |
         static_cast<std::uint32_t>(candidate.endpoints[2]) << 16 | static_cast<std::uint32_t>(candidate.endpoints[3]) << 24;
}

// Coordinate descent over the listed endpoints (strict improvements, fixed order). While one endpoint moves, the
// other channel's terms are fixed and computed once; a trial only has to tell whether it beats `current`. A point
// the descent has already visited is not evaluated again (about 30 % of the second pass's trials at medium): its
// error was at least the current error of its time, and the current error only decreases, so it cannot win.
double descend(const TrialTexels& texels, const SearchEffort& effort, const std::vector<int>& parameters,
               Candidate& candidate, double current) {
  const LuminanceBlockError& error = *texels.error;
  std::vector<std::uint32_t> visited = {endpoint_key(candidate)};
  for (int pass = 0; pass < effort.descent_passes; ++pass) {
    bool improved = false;
    for (const int parameter : parameters) {
      const int channel = parameter / 2;
      const ChannelParts fixed = channel_parts(error, candidate, 1 - channel);
      const int original = candidate.endpoints[parameter];
      int best_value = original;
      for (const int step : effort.descent_steps)
        for (const int value : {original - step, original + step}) {
          if (value < 0 || value > 255 || value == original) continue;
          candidate.endpoints[parameter] = value;
          const std::uint32_t key = endpoint_key(candidate);
          if (pass > 0 && std::find(visited.begin(), visited.end(), key) != visited.end()) continue;
          visited.push_back(key);
          const ChannelParts moved = channel_parts(error, candidate, channel);
          const double trial = channel == 0 ? evaluate(texels, moved, fixed, nullptr, nullptr, current)
                                            : evaluate(texels, fixed, moved, nullptr, nullptr, current);
          if (trial < current) {
            current = trial;
            best_value = value;
            improved = true;
          }
        }
      candidate.endpoints[parameter] = best_value;
    }
    if (!improved) break;
  }
  return current;
}

// The BC4 search for one channel's eq. 3 targets. In a block inside one zone the other channel's targets are all
// its constant, 0 or 255: the endpoints (v, v) fit them with error 0, which no refinement step can beat (they
// accept strict improvements only), so every search returns the fast path's answer, and the fast path is taken.
S3tcSearch start_search(const float targets[16], S3tcSearch search) {
  const float value = targets[0];
  if (value != std::nearbyint(value)) return search;
  for (int texel = 1; texel < 16; ++texel)
    if (targets[texel] != value) return search;
  return S3tcSearch::fast;
}

Bc4Params to_params(const Candidate& candidate, int channel, const std::uint8_t* codes) {
  Bc4Params params;
  params.endpoints = {candidate.endpoints[2 * channel], candidate.endpoints[2 * channel + 1]};
  params.mode = candidate.modes[channel];
  std::copy(codes, codes + 16, params.indices.begin());
  return canonicalise_bc4(params);
}

}  // namespace

void alpha_parts(const LuminanceBlockError& error, const Bc4Params& tex0, const Bc4Params& tex1, double part0[8],
                 double part1[8]) {
  int q0[8], q1[8];
  fetched_alpha_codes(tex0.endpoints[0], tex0.endpoints[1], tex0.mode, q0);
  fetched_alpha_codes(tex1.endpoints[0], tex1.endpoints[1], tex1.mode, q1);
  const double* fractions = code_fractions();   // the same doubles as code / 255.0
  for (int code = 0; code < 8; ++code) {
    part0[code] = fractions[q0[code]] * error.high;
    part1[code] = fractions[q1[code]] * error.low + error.tmin;
  }
}

void decoded_luminance(const LuminanceBlockError& error, const Bc4Params& tex0, const Bc4Params& tex1,
                       double out[16]) {
  double part0[8], part1[8];
  alpha_parts(error, tex0, tex1, part0, part1);
  for (int texel = 0; texel < 16; ++texel) out[texel] = part0[tex0.indices[texel] & 7] + part1[tex1.indices[texel] & 7];
}

double luminance_error_with_codes(const LuminanceBlockError& error, const Bc4Params& tex0, const Bc4Params& tex1) {
  double decoded[16];
  decoded_luminance(error, tex0, tex1, decoded);
  double total = 0.0;
  for (int texel = 0; texel < 16; ++texel)
    total += error.weight[texel] * std::abs(error.luminance[texel] - decoded[texel]);
  return total;
}

LuminanceFit fit_luminance_block(const LuminanceBlockError& error, const Zones& zones, LuminanceSplit split,
                                 const SearchEffort& effort, Codec codec, const BlockSolverSetup& solver,
                                 std::size_t block_index) {
  // The plain BC3 alpha fit of the eq. 3 targets: the bc3 codec's answer and the 1D codec's start.
  float targets[2][16];
  bool has_low = false, has_high = false;
  for (int texel = 0; texel < 16; ++texel) {
    const std::array<double, 2> t = luminance_targets(error.luminance[texel], zones, split);
    targets[0][texel] = static_cast<float>(t[0] * 255.0);
    targets[1][texel] = static_cast<float>(t[1] * 255.0);
    (error.luminance[texel] <= zones.t1 ? has_low : has_high) = true;
  }
  LuminanceFit fit;
  // The 1D codec descends from every mode pair of the start's endpoints, so its start is an 8-value fit alone, at
  // the preset's luminance_start effort (measured on the 28 HDR images with the refined start and 2 passes of steps
  // +-1..16, 2026-11-27: the 6-value start cost 8 % of the encode time, and without it the mean log2[RGB] went
  // 1.041 -> 1.031, mPSNR 39.70 -> 39.84 dB, psnr_li2005 61.45 -> 61.50 dB).
  const bool six_value_start = codec == Codec::bc3;
  const S3tcSearch search = codec == Codec::bc3 ? effort.s3tc : effort.luminance_start;
  fit.tex0 = fit_bc4_block(targets[0], start_search(targets[0], search), six_value_start);
  fit.tex1 = fit_bc4_block(targets[1], start_search(targets[1], search), six_value_start);
  fit.error = luminance_error_with_codes(error, fit.tex0, fit.tex1);
  if (codec == Codec::bc3) return fit;

  Candidate start;
  start.endpoints[0] = fit.tex0.endpoints[0];
  start.endpoints[1] = fit.tex0.endpoints[1];
  start.endpoints[2] = fit.tex1.endpoints[0];
  start.endpoints[3] = fit.tex1.endpoints[1];
  start.modes[0] = fit.tex0.mode;
  start.modes[1] = fit.tex1.mode;

  // Which channels the search moves: both for 1x12 and mixed blocks; a one-zone block its own (tex1.a for the low
  // zone, tex0.a for the high zone), unless the preset searches the other too.
  const bool both = split == LuminanceSplit::one_range || effort.search_inactive_channel || (has_low && has_high);
  const bool active[2] = {both || has_high, both || has_low};
  std::vector<Bc4Mode> mode_choices[2];
  for (int channel = 0; channel < 2; ++channel) {
    if (active[channel])
      mode_choices[channel] = {Bc4Mode::eight_value, Bc4Mode::six_value};
    else
      mode_choices[channel] = {start.modes[channel]};
  }
  std::vector<int> parameters;
  for (int channel = 0; channel < 2; ++channel)
    if (active[channel]) {
      parameters.push_back(2 * channel);
      parameters.push_back(2 * channel + 1);
    }

  // Every mode pair's answer competes (the start's pair among them, and descent never worsens it); a solver's answer
  // is taken as the solver returned it, not min'ed with the start.
  const TrialTexels texels = make_trial_texels(error);
  Candidate best = start;
  double best_error = std::numeric_limits<double>::infinity();
  for (const Bc4Mode mode0 : mode_choices[0])
    for (const Bc4Mode mode1 : mode_choices[1]) {
      Candidate candidate = start;
      candidate.modes[0] = mode0;
      candidate.modes[1] = mode1;
      double candidate_error;
      if (solver.builtin()) {
        candidate_error = descend(texels, effort, parameters, candidate, evaluate(texels, candidate, nullptr, nullptr));
      } else {
        LuminanceBlockError problem_error = error;
        problem_error.modes = {mode0, mode1};
        problem_error.texture_unit = true;
        const auto problem = make_luminance_block_problem(problem_error);
        const std::vector<double> x0 = {double(start.endpoints[0]), double(start.endpoints[1]),
                                        double(start.endpoints[2]), double(start.endpoints[3])};
        const std::vector<std::int64_t> answer = solve_block_on_lattice(solver, problem, x0, block_index);
        for (int k = 0; k < 4; ++k) candidate.endpoints[k] = static_cast<int>(answer[k]);
        candidate_error = evaluate(texels, candidate, nullptr, nullptr);
      }
      if (candidate_error < best_error) {
        best_error = candidate_error;
        best = candidate;
      }
    }
  std::uint8_t codes[2][16];
  fit.error = evaluate(texels, best, codes[0], codes[1]);
  fit.tex0 = to_params(best, 0, codes[0]);
  fit.tex1 = to_params(best, 1, codes[1]);
  return fit;
}

}  // namespace wang
}  // namespace blocklab
