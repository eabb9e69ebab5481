// Coordinate-descent polish of quantised endpoints (see bc7_endpoint_polish.h).
//
// A trial changes one code of one lane, so only that lane's column of the palette changes: the per-lane squared
// distances of every (palette entry, texel) pair are kept, a trial recomputes one lane's distances and takes each
// texel's minimum over the whole palette (index choice exhaustive, never worse than assign_indices' nearest-two
// rule).
#include "formats/bc7/bc7_endpoint_polish.h"

#include <algorithm>
#include <cmath>

#include "formats/bc7/bc7_tables.h"

namespace blocklab {
namespace bc7 {

namespace {

struct PaletteDistances {
  int palette_size = 0;
  int count = 0;
  float lane_distance[4][16][16] = {};   // [lane][entry][texel]: weight * (texel - palette entry)^2
  float distance[16][16] = {};           // [entry][texel]: summed over the lanes

  // Lane `lane`'s distances for endpoints e0, e1 into out[entry][texel].
  void lane_distances(const float (*texels)[4], const int* index_weight, int lane, float weight, int e0, int e1,
                      float (&out)[16][16]) const {
    for (int k = 0; k < palette_size; ++k) {
      const float value = static_cast<float>(interpolate(e0, e1, index_weight[k]));
      for (int i = 0; i < count; ++i) {
        const float difference = texels[i][lane] - value;
        out[k][i] = weight * difference * difference;
      }
    }
  }

  // Sum over texels of the smallest distance over the palette, with lane `lane` replaced by `replacement`.
  float error_with_lane(int lane, const float (&replacement)[16][16]) const {
    float best[16];
    for (int i = 0; i < count; ++i) best[i] = INFINITY;
    for (int k = 0; k < palette_size; ++k)
      for (int i = 0; i < count; ++i)
        best[i] = std::min(best[i], distance[k][i] - lane_distance[lane][k][i] + replacement[k][i]);
    float total = 0.0f;
    for (int i = 0; i < count; ++i) total += best[i];
    return total;
  }
};

}  // namespace

void polish_endpoints(const float (*texels)[4], int count, int index_bits, const EndpointLattice& lattice,
                      const float weights[4], int max_passes, QuantisedEndpoints& endpoints, std::uint8_t* indices,
                      float& error) {
  const int* index_weight = index_weights(index_bits);
  const bool has_pbit = lattice.pbit != PbitKind::none;
  int lanes[4], lane_count = 0;
  for (int lane = 0; lane < 4; ++lane)
    if (lattice.lane_bits[lane] > 0 && weights[lane] > 0.0f) lanes[lane_count++] = lane;
  if (lane_count == 0 || count == 0) return;

  PaletteDistances table;
  table.palette_size = 1 << index_bits;
  table.count = count;
  const auto rebuild = [&]() {
    for (int k = 0; k < table.palette_size; ++k)
      for (int i = 0; i < count; ++i) table.distance[k][i] = 0.0f;
    for (int l = 0; l < lane_count; ++l) {
      const int lane = lanes[l];
      table.lane_distances(texels, index_weight, lane, weights[lane], endpoints.expanded[0][lane],
                           endpoints.expanded[1][lane], table.lane_distance[lane]);
      for (int k = 0; k < table.palette_size; ++k)
        for (int i = 0; i < count; ++i) table.distance[k][i] += table.lane_distance[lane][k][i];
    }
  };
  rebuild();

  bool moved = false;
  float trial_distance[16][16];
  for (int pass = 0; pass < max_passes && error > 0.0f; ++pass) {
    bool improved = false;
    for (int endpoint = 0; endpoint < 2; ++endpoint)
      for (int l = 0; l < lane_count; ++l) {
        const int lane = lanes[l], bits = lattice.lane_bits[lane];
        const int pbit = has_pbit ? endpoints.pbits[endpoint] : -1;
        for (const int step : {-1, 1}) {
          const int code = endpoints.codes[endpoint][lane] + step;
          if (code < 0 || code > (1 << bits) - 1) continue;
          const int expanded = expand_code(code, bits, pbit);
          const int e0 = endpoint == 0 ? expanded : endpoints.expanded[0][lane];
          const int e1 = endpoint == 1 ? expanded : endpoints.expanded[1][lane];
          table.lane_distances(texels, index_weight, lane, weights[lane], e0, e1, trial_distance);
          if (!(table.error_with_lane(lane, trial_distance) < error)) continue;
          endpoints.codes[endpoint][lane] = static_cast<std::uint8_t>(code);
          endpoints.expanded[endpoint][lane] = expanded;
          error = table.error_with_lane(lane, trial_distance);
          for (int k = 0; k < table.palette_size; ++k)
            for (int i = 0; i < count; ++i) {
              table.distance[k][i] += trial_distance[k][i] - table.lane_distance[lane][k][i];
              table.lane_distance[lane][k][i] = trial_distance[k][i];
            }
          improved = moved = true;
          break;   // this code moved; its other direction is tried in the next pass
        }
      }
    if (!improved) break;
  }
  if (!moved) return;
  rebuild();   // from scratch: the final error carries no rounding of the incremental updates
  // Indices of the final endpoints: each texel's nearest palette entry (ties: the lower index).
  float total = 0.0f;
  for (int i = 0; i < count; ++i) {
    int best = 0;
    for (int k = 1; k < table.palette_size; ++k)
      if (table.distance[k][i] < table.distance[best][i]) best = k;
    indices[i] = static_cast<std::uint8_t>(best);
    total += table.distance[best][i];
  }
  error = total;
}

}  // namespace bc7
}  // namespace blocklab
