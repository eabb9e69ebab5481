// The BC1/BC3 colour encoder: endpoint search for one 4x4 block of RGB texels.
//
// Pipeline (formats/bc1/README.md has the measured effect of each step):
//   1. single colour: the mean colour's optimal endpoints from precomputed per-channel tables (the 2/3 point of
//      the 4-colour palette or the midpoint of the 3-colour palette can reproduce a value the 565 endpoints
//      cannot) -- a candidate for every block, the answer for flat blocks (s3tc_single_color.cpp);
//   2. principal axis of the weighted colour covariance (power iteration, s3tc_principal_axis.cpp);
//   3. cluster fit (Brown's squish "ClusterFit" idea): the texels sorted along the axis, every partition of the
//      order into 4 (or 3) consecutive runs is one index assignment; for each, the least-squares endpoints come in
//      closed form from prefix sums, are quantised to RGB565 and scored with the closed-form error of the
//      QUANTISED endpoints (s3tc_cluster_fit.cpp);
//   4. polish on the real palette: optimal indices for the quantised endpoints, least-squares refit of the
//      endpoints for those indices, then hill climbing of the six 565 coordinates by +-1 (s3tc_color_refine.cpp);
//   5. (exhaustive only) every point of the +-1 neighbourhood of the polished endpoints (3^6 = 729 per mode).
// `fast` skips 1 and 3 (bounding box of the projections on the axis + two least-squares rounds, 4-colour only).
// Errors are per-channel weighted sums of squared differences in 8-bit code units, evaluated on the reference
// decoding's palette (exact fractions of bit-replicated endpoints), so what the encoder minimises is what the
// metrics measure.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "formats/bc1/bc1_block.h"

namespace blocklab {

enum class S3tcSearch { fast, standard, exhaustive };

// The option `search` of the S3TC codecs: "fast", "default" (S3tcSearch::standard), "exhaustive" (OptionTable choices).
std::vector<std::pair<std::string, S3tcSearch>> s3tc_search_choices();
// "r,g,b": three finite non-negative reals, not all zero; throws Error("<who>: option 'weights' ...").
std::array<float, 3> parse_channel_weights(const std::string& text, const std::string& who);

// One block as the colour encoder sees it.
struct ColorBlock {
  float texels[16][3];    // RGB in 8-bit code units, clamped to [0, 255]
  float weights[3];       // per-channel error weights
};

// RGB of `texels` (values in [0, 1]; above 1 clamps to 255, below 0 and NaN to 0) scaled to 8-bit code units.
ColorBlock make_color_block(const BlockTexels& texels, const std::array<float, 3>& weights);

struct ColorFitSettings {
  S3tcSearch search = S3tcSearch::standard;
  bool allow_three_color = true;   // BC1: true; BC3: false (its colour block is always 4-colour)
};

// The encoder. Returns a canonical block: for BC1 (allow_three_color) canonicalise_bc1's form, for BC3
// canonicalise_bc3_color's form (color0 > color1, or equal endpoints with every code 0).
Bc1Params fit_color_block(const ColorBlock& block, const ColorFitSettings& settings);

// ---- the pieces (exposed for tests and for other S3TC-style encoders) -------------------------------------------

// Endpoints on the RGB565 lattice plus a mode: one point of the endpoint search space.
struct ColorCandidate {
  std::array<std::array<int, 3>, 2> endpoints{};
  Bc1Mode mode = Bc1Mode::four_color;
};

// The weighted squared error of `block` under `candidate`'s real palette with the best code per texel (written to
// `indices` when not null). Ties between codes go to the lower code.
float evaluate_color_candidate(const ColorBlock& block, const ColorCandidate& candidate, std::uint8_t* indices);

// Nearest RGB565 lattice value of an 8-bit-unit real (any value; clamped to [0, 255] first): the q whose
// bit-replicated expansion is closest.
int quantize_to_565_channel(float value, int channel);

// Best endpoints for a single colour (per channel, from exhaustive tables over all endpoint pairs) in `mode`.
ColorCandidate single_color_candidate(const float rgb[3], Bc1Mode mode);

// Unit principal axis (weighted space scaled back to RGB) of the block's colours; a grey diagonal when the block
// has (almost) no variance.
std::array<float, 3> principal_axis(const ColorBlock& block);

// Cluster fit over the texels ordered along `axis`; `mode` selects the 4-run (four_color) or 3-run (three_color)
// partitions. Returns the best quantised candidate by the closed-form error.
ColorCandidate cluster_fit(const ColorBlock& block, const std::array<float, 3>& axis, Bc1Mode mode);
// The same search on a chosen code path (all return the same candidate; for tests and measurements): `automatic`
// (AVX2 when the CPU has it, else SSE2 / portable), `portable` (SSE2 on x86-64), `avx2` (falls back to portable
// when unavailable), `unpruned` (portable, every partition scored in order, no lower-bound pruning).
enum class ClusterFitPath { automatic, portable, avx2, unpruned };
ColorCandidate cluster_fit(const ColorBlock& block, const std::array<float, 3>& axis, Bc1Mode mode,
                           ClusterFitPath path);
// Whether this CPU runs cluster_fit's AVX2 path.
bool cluster_fit_avx2_available();

// Least-squares endpoints for fixed codes (black texels of the 3-colour mode ignored), quantised to 565. Returns
// false (candidate untouched) when the codes do not determine both endpoints.
bool least_squares_candidate(const ColorBlock& block, const std::uint8_t* indices, ColorCandidate& candidate);

// Alternating refinement + +-1 hill climbing from `candidate`; returns the improved candidate and its error.
float polish_color_candidate(const ColorBlock& block, ColorCandidate& candidate, int hill_climb_passes);

// Every point of the +-radius neighbourhood of `candidate` (clamped to the lattice); keeps the best.
float exhaustive_color_neighbourhood(const ColorBlock& block, ColorCandidate& candidate, int radius);

}  // namespace blocklab
