// Per-lane rounding of ideal endpoints for fixed indices (see bc7_endpoint_rounding.h).
#include "formats/bc7/bc7_endpoint_rounding.h"

#include <cmath>

#include "formats/bc7/bc7_tables.h"

namespace blocklab {
namespace bc7 {

namespace {

// The codes of a lane that bracket `value`: its nearest code and, unless that code expands to `value` exactly or
// the lattice ends there, the neighbour on the other side of `value`. Returns how many (1 or 2).
int bracketing_codes(float value, int bits, int pbit, int (&codes)[2]) {
  const int nearest = quantise_channel(value, bits, pbit);
  const float expanded = static_cast<float>(expand_code(nearest, bits, pbit));
  codes[0] = nearest;
  const int other = expanded > value ? nearest - 1 : nearest + 1;
  if (expanded == value || other < 0 || other > (1 << bits) - 1) return 1;
  codes[1] = other;
  return 2;
}

}  // namespace

QuantisedEndpoints round_endpoints_for_indices(const float (*texels)[4], int count, const std::uint8_t* indices,
                                               int index_bits, const float ideal[2][4], const EndpointLattice& lattice,
                                               const float weights[4], bool all_pbits, float* error) {
  const int* index_weight = index_weights(index_bits);
  int weight_of[16];
  for (int i = 0; i < count; ++i) weight_of[i] = index_weight[indices[i]];
  int combos[4][2];
  const int combo_count = pbit_candidates(ideal, lattice, weights, all_pbits, combos);
  const bool has_pbit = lattice.pbit != PbitKind::none;

  QuantisedEndpoints best;
  float best_total = INFINITY;
  for (int combo = 0; combo < combo_count; ++combo) {
    QuantisedEndpoints rounded;
    const int pbit_of[2] = {has_pbit ? combos[combo][0] : -1, has_pbit ? combos[combo][1] : -1};
    for (int endpoint = 0; endpoint < 2; ++endpoint)
      rounded.pbits[endpoint] = static_cast<std::uint8_t>(has_pbit ? pbit_of[endpoint] : 0);
    float total = 0.0f;
    for (int lane = 0; lane < 4 && total < best_total; ++lane) {
      const int bits = lattice.lane_bits[lane];
      if (bits == 0) {   // lane not stored (alpha of modes 0-3): decodes to 255
        rounded.codes[0][lane] = rounded.codes[1][lane] = 0;
        rounded.expanded[0][lane] = rounded.expanded[1][lane] = 255;
        continue;
      }
      int candidates[2][2];
      const int candidate_count[2] = {bracketing_codes(ideal[0][lane], bits, pbit_of[0], candidates[0]),
                                      bracketing_codes(ideal[1][lane], bits, pbit_of[1], candidates[1])};
      int best_pair[2] = {candidates[0][0], candidates[1][0]};
      if (weights[lane] > 0.0f) {
        int expanded[2][2];
        for (int endpoint = 0; endpoint < 2; ++endpoint)
          for (int c = 0; c < candidate_count[endpoint]; ++c)
            expanded[endpoint][c] = expand_code(candidates[endpoint][c], bits, pbit_of[endpoint]);
        float best_lane = INFINITY;
        for (int a = 0; a < candidate_count[0]; ++a)
          for (int b = 0; b < candidate_count[1]; ++b) {
            const int e0 = expanded[0][a], e1 = expanded[1][b];
            float lane_error = 0.0f;
            for (int i = 0; i < count; ++i) {
              const float difference = texels[i][lane] - static_cast<float>(interpolate(e0, e1, weight_of[i]));
              lane_error += difference * difference;
            }
            if (lane_error < best_lane) {   // strict: ties keep the nearest codes (tried first)
              best_lane = lane_error;
              best_pair[0] = candidates[0][a];
              best_pair[1] = candidates[1][b];
            }
          }
        total += weights[lane] * best_lane;
      }
      for (int endpoint = 0; endpoint < 2; ++endpoint) {
        rounded.codes[endpoint][lane] = static_cast<std::uint8_t>(best_pair[endpoint]);
        rounded.expanded[endpoint][lane] = expand_code(best_pair[endpoint], bits, pbit_of[endpoint]);
      }
    }
    if (total < best_total) {
      best_total = total;
      best = rounded;
    }
  }
  *error = best_total;
  return best;
}

}  // namespace bc7
}  // namespace blocklab
