// Per-block BC7 mode and partition search (see bc7_mode_search.h).
#include "formats/bc7/bc7_mode_search.h"

#include <algorithm>
#include <cmath>

#include "formats/bc7/bc7_decode.h"
#include "formats/bc7/bc7_endpoint_fit.h"
#include "formats/bc7/bc7_partition_estimate.h"
#include "formats/bc7/bc7_partition_palette_estimate.h"

namespace blocklab {
namespace bc7 {

namespace {

struct BlockSearch {
  const std::uint8_t (&rgba)[kTexels][4];
  const EncoderSettings& settings;
  float texels[kTexels][4];
  bool opaque = true;
  Params best;
  double best_error = INFINITY;
  // Lattice polish passes of the current fits: 0 during the search; settings.polish_passes when the winner is
  // fitted again at the end (polishing only the chosen candidate costs one fit instead of one per candidate).
  int polish_passes = 0;
  // The search call that produced `best`: try_partition(mode, partition) or try_separate_alpha(mode, rotation,
  // selection), kept so it can be repeated with the polish on.
  int best_call[3] = {-1, 0, 0};

  BlockSearch(const std::uint8_t (&source)[kTexels][4], const EncoderSettings& s) : rgba(source), settings(s) {
    for (int i = 0; i < kTexels; ++i) {
      for (int c = 0; c < 4; ++c) texels[i][c] = static_cast<float>(rgba[i][c]);
      if (rgba[i][3] != 255) opaque = false;
    }
  }

  bool consider(const Params& candidate) { return consider(candidate, block_error(candidate, rgba, settings.weights)); }

  // Keeps `candidate` if it is strictly better (ties keep the earlier candidate: deterministic); true if kept.
  bool consider(const Params& candidate, double error) {
    if (!(error < best_error)) return false;
    best_error = error;
    best = candidate;
    return true;
  }

  // Modes 0, 1, 2, 3, 6, 7: every subset fitted on all its stored lanes with the mode's one index set.
  void try_partition(int mode, int partition) {
    const ModeInfo& info = mode_info(mode);
    SubsetFitSettings fit_settings;
    fit_settings.index_bits = info.index_bits;
    fit_settings.lattice.lane_bits[0] = fit_settings.lattice.lane_bits[1] = fit_settings.lattice.lane_bits[2] =
        info.color_bits;
    fit_settings.lattice.lane_bits[3] = info.alpha_bits;
    fit_settings.lattice.pbit =
        info.endpoint_pbits ? PbitKind::per_endpoint : (info.shared_pbits ? PbitKind::shared : PbitKind::none);
    // Opaque block in a mode that stores alpha with a P-bit (6, 7): alpha 255 = all ones needs P-bit 1.
    fit_settings.lattice.force_pbit_one = opaque && info.alpha_bits > 0 && fit_settings.lattice.pbit != PbitKind::none;
    std::copy(settings.weights, settings.weights + 4, fit_settings.weights);
    // Alpha not stored (decodes to 255), or opaque with P-bit 1 forced (stored 255 exactly): alpha error is 0.
    if (info.alpha_bits == 0 || opaque) fit_settings.weights[3] = 0.0f;
    fit_settings.refine_iterations = settings.refine_iterations;
    fit_settings.pbit_search = settings.pbit_search;
    fit_settings.polish_passes = polish_passes;

    Params params;
    params.mode = mode;
    params.partition = partition;
    const std::uint8_t* subsets = partition_subsets(info.subset_count, partition);
    const int half_palette = 1 << (info.index_bits - 1);
    // The subsets' fit errors are measured on the exactly decoded palette (alpha: not stored, or stored 255
    // exactly, when its weight is 0 here), so their sum is the block's error: a partial sum that already reaches
    // the best block so far ends this candidate.
    double error = 0.0;
    for (int subset = 0; subset < info.subset_count; ++subset) {
      float members[kTexels][4];
      int member_texel[kTexels];
      int count = 0;
      for (int texel = 0; texel < kTexels; ++texel)
        if (subsets[texel] == subset) {
          std::copy(texels[texel], texels[texel] + 4, members[count]);
          member_texel[count++] = texel;
        }
      SubsetFit fit = fit_subset(members, count, fit_settings);
      error += fit.error;
      if (!(error < best_error)) return;
      // The anchor texel's index is stored without its MSB: if it is set, mirror the subset (same decoded texels).
      const int anchor = anchor_texel(info.subset_count, partition, subset);
      const int anchor_member = static_cast<int>(std::find(member_texel, member_texel + count, anchor) - member_texel);
      if (fit.indices[anchor_member] >= half_palette) swap_endpoints(fit, info.index_bits, count);
      for (int endpoint = 0; endpoint < 2; ++endpoint) {
        for (int lane = 0; lane < 4; ++lane) params.endpoints[subset][endpoint][lane] = fit.endpoints.codes[endpoint][lane];
        params.pbits[subset][endpoint] = fit.endpoints.pbits[endpoint];
      }
      for (int m = 0; m < count; ++m) params.indices[member_texel[m]] = fit.indices[m];
    }
    if (consider(params, error)) best_call[0] = mode, best_call[1] = partition, best_call[2] = -1;
  }

  // Modes 4, 5: colour (three lanes, one of them alpha after a rotation) and a scalar channel with separate
  // index sets.
  void try_separate_alpha(int mode, int rotation, int index_selection) {
    const ModeInfo& info = mode_info(mode);
    // Rotation r > 0 stores channel r-1 in the alpha slot and alpha in channel r-1's colour slot.
    const int scalar_channel = rotation > 0 ? rotation - 1 : 3;
    const int colour_index_bits = index_selection ? info.index2_bits : info.index_bits;
    const int scalar_index_bits = index_selection ? info.index_bits : info.index2_bits;

    float colour[kTexels][4], scalar[kTexels][4];
    SubsetFitSettings colour_settings, scalar_settings;
    for (int lane = 0; lane < 3; ++lane) {
      const int source = lane == scalar_channel ? 3 : lane;
      colour_settings.weights[lane] = settings.weights[source];
      colour_settings.lattice.lane_bits[lane] = info.color_bits;
      for (int i = 0; i < kTexels; ++i) colour[i][lane] = texels[i][source];
    }
    colour_settings.weights[3] = 0.0f;
    colour_settings.lattice.lane_bits[3] = 0;
    for (int i = 0; i < kTexels; ++i) {
      colour[i][3] = 255.0f;
      scalar[i][0] = texels[i][scalar_channel];
      scalar[i][1] = scalar[i][2] = scalar[i][3] = 0.0f;
    }
    scalar_settings.weights[0] = settings.weights[scalar_channel];
    scalar_settings.weights[1] = scalar_settings.weights[2] = scalar_settings.weights[3] = 0.0f;
    scalar_settings.lattice.lane_bits[0] = info.alpha_bits;
    colour_settings.index_bits = colour_index_bits;
    scalar_settings.index_bits = scalar_index_bits;
    colour_settings.refine_iterations = scalar_settings.refine_iterations = settings.refine_iterations;
    colour_settings.pbit_search = scalar_settings.pbit_search = false;   // modes 4/5 have no P-bits
    colour_settings.polish_passes = scalar_settings.polish_passes = polish_passes;

    SubsetFit colour_fit = fit_subset(colour, kTexels, colour_settings);
    SubsetFit scalar_fit = fit_subset(scalar, kTexels, scalar_settings);
    // Texel 0 anchors both index sets.
    if (colour_fit.indices[0] >= (1 << (colour_index_bits - 1))) swap_endpoints(colour_fit, colour_index_bits, kTexels);
    if (scalar_fit.indices[0] >= (1 << (scalar_index_bits - 1))) swap_endpoints(scalar_fit, scalar_index_bits, kTexels);

    Params params;
    params.mode = mode;
    params.rotation = rotation;
    params.index_selection = index_selection;
    for (int endpoint = 0; endpoint < 2; ++endpoint) {
      for (int lane = 0; lane < 3; ++lane) params.endpoints[0][endpoint][lane] = colour_fit.endpoints.codes[endpoint][lane];
      params.endpoints[0][endpoint][3] = scalar_fit.endpoints.codes[endpoint][0];
    }
    std::uint8_t* colour_indices = index_selection ? params.indices2 : params.indices;
    std::uint8_t* scalar_indices = index_selection ? params.indices : params.indices2;
    std::copy(colour_fit.indices, colour_fit.indices + kTexels, colour_indices);
    std::copy(scalar_fit.indices, scalar_fit.indices + kTexels, scalar_indices);
    if (consider(params)) best_call[0] = mode, best_call[1] = rotation, best_call[2] = index_selection;
  }

  void run() {
    bool enabled[kModeCount];
    std::copy(opaque ? settings.mode_enabled : settings.alpha_mode_enabled,
              (opaque ? settings.mode_enabled : settings.alpha_mode_enabled) + kModeCount, enabled);
    if (!opaque) {
      // Translucent block: only modes that store alpha.
      for (int mode = 0; mode < 4; ++mode) enabled[mode] = false;
      if (!enabled[4] && !enabled[5] && !enabled[6] && !enabled[7]) enabled[6] = true;   // documented fallback
    }
    // Partition rankings, computed once per (subset count, partition count) and shared by the modes.
    int ranked[2][2][64];
    float ranked_estimate[2][2][64];
    int ranked_count[2][2] = {{-1, -1}, {-1, -1}};
    // Projections of the ranked partitions on their subsets' axes, made on first use and shared by the modes.
    // Keyed by subset count and partition number (mode 0's 16 partitions are the first 16 of mode 2's 64).
    PartitionProjection projection[2][64];
    bool projected[2][64] = {};
    float estimate_weights[4];
    std::copy(settings.weights, settings.weights + 4, estimate_weights);
    if (opaque) estimate_weights[3] = 0.0f;   // constant 255: contributes nothing

    // One-subset modes first: their single fit is cheap and gives the bound that ends the partitioned modes'
    // candidates early (a partial sum over the subsets that already reaches it).
    constexpr int kSearchOrder[kModeCount] = {6, 5, 4, 1, 3, 7, 0, 2};
    for (int position = 0; position < kModeCount && best_error > 0.0; ++position) {
      const int mode = kSearchOrder[position];
      if (!enabled[mode]) continue;
      // Three-subset modes only for blocks the modes before them left with a large error: they cost the ranking of
      // 64 partitions and gain little on blocks that are already close (three_subset_threshold).
      if (mode_info(mode).subset_count == 3 && best_error < settings.three_subset_threshold) continue;
      const ModeInfo& info = mode_info(mode);
      if (info.subset_count > 1) {
        const int partition_count = 1 << info.partition_bits;
        const int s = info.subset_count - 2, p = partition_count == 64 ? 1 : 0;
        if (ranked_count[s][p] < 0)
          ranked_count[s][p] = rank_partitions(texels, estimate_weights, info.subset_count, partition_count,
                                               std::max(settings.partitions_to_refine, settings.partition_candidates),
                                               ranked[s][p], ranked_estimate[s][p]);
        // The estimate is the error of the best continuous line through each subset, with every texel placed
        // anywhere on it: a fit with a few palette entries on (nearly) that line does not get below it, so once
        // the estimates (ascending) reach the best error so far, the remaining partitions are skipped.
        if (settings.partition_candidates <= settings.partitions_to_refine) {
          for (int k = 0; k < ranked_count[s][p] && ranked_estimate[s][p][k] < best_error; ++k)
            try_partition(mode, ranked[s][p][k]);
          continue;
        }
        // Second stage: the candidates re-ranked by the palette estimate for this mode's index bits; the best
        // partitions_to_refine are fitted (those whose line error already reaches the best error are skipped).
        int order[64];
        float palette_estimate[64];
        int candidates = 0;
        for (int k = 0; k < ranked_count[s][p] && ranked_estimate[s][p][k] < best_error; ++k) {
          const int partition = ranked[s][p][k];
          if (!projected[s][partition]) {
            projection[s][partition] = project_partition(texels, estimate_weights, info.subset_count, partition);
            projected[s][partition] = true;
          }
          palette_estimate[k] = palette_line_estimate(projection[s][partition], info.index_bits);
          order[candidates++] = k;
        }
        const int fitted = std::min(candidates, settings.partitions_to_refine);
        std::partial_sort(order, order + fitted, order + candidates, [&](int a, int b) {
          return palette_estimate[a] < palette_estimate[b] || (palette_estimate[a] == palette_estimate[b] && a < b);
        });
        for (int j = 0; j < fitted; ++j)
          if (ranked_estimate[s][p][order[j]] < best_error) try_partition(mode, ranked[s][p][order[j]]);
      } else if (info.index2_bits == 0) {
        try_partition(mode, 0);   // mode 6
      } else {
        const int rotation_count = settings.rotation_search ? 4 : 1;
        const int selection_count = info.index_selection_bits ? 2 : 1;
        for (int rotation = 0; rotation < rotation_count; ++rotation)
          for (int selection = 0; selection < selection_count; ++selection) try_separate_alpha(mode, rotation, selection);
      }
    }
    // The winner fitted again with the lattice polish; kept only if that is strictly better.
    if (settings.polish_passes > 0 && best_error > 0.0 && best_call[0] >= 0) {
      polish_passes = settings.polish_passes;
      const int call[3] = {best_call[0], best_call[1], best_call[2]};
      if (call[2] < 0) try_partition(call[0], call[1]);
      else try_separate_alpha(call[0], call[1], call[2]);
    }
  }
};

}  // namespace

double block_error(const Params& params, const std::uint8_t (&rgba)[kTexels][4], const float weights[4]) {
  int decoded[kTexels][4];
  decode(params, decoded);
  double error = 0.0;
  for (int i = 0; i < kTexels; ++i)
    for (int c = 0; c < 4; ++c) {
      const double difference = decoded[i][c] - rgba[i][c];
      error += weights[c] * difference * difference;
    }
  return error;
}

Params encode_block(const std::uint8_t (&rgba)[kTexels][4], const EncoderSettings& settings) {
  BlockSearch search(rgba, settings);
  search.run();
  return search.best;
}

}  // namespace bc7
}  // namespace blocklab
