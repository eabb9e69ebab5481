// Endpoint quantisation with P-bits (KDFS "BPTC" endpoint expansion; SPECS.md 2.3 and 2.5 item 4).
#include "formats/bc7/bc7_quantise.h"

#include <cmath>
#include <cstdlib>

#include "formats/bc7/bc7_tables.h"

namespace blocklab {
namespace bc7 {

int expand_code(int code, int bits, int pbit) {
  if (pbit < 0) return expand_endpoint(code, bits);
  return expand_endpoint((code << 1) | pbit, bits + 1);
}

namespace {

// nearest[bits][pbit + 1][v] = nearest stored code to the 8-bit value v (bits 1..8; pbit -1 = none, 0, 1), ties
// to the lower code; built once by exhaustive search over the codes (at most 256 x 256 per table).
struct NearestCodeTable {
  std::uint8_t nearest[9][3][256];
  NearestCodeTable() {
    for (int bits = 1; bits <= 8; ++bits)
      for (int pbit = -1; pbit <= 1; ++pbit)
        for (int value = 0; value < 256; ++value) {
          int best_code = 0, best_distance = 1 << 20;
          for (int code = 0; code < (1 << bits); ++code) {
            // An 8-bit code with a P-bit would be 9 bits: BC7 never has it (alpha of mode 5 has no P-bit).
            if (pbit >= 0 && bits >= 8) break;
            const int distance = std::abs(expand_code(code, bits, pbit) - value);
            if (distance < best_distance) {
              best_distance = distance;
              best_code = code;
            }
          }
          nearest[bits][pbit + 1][value] = static_cast<std::uint8_t>(best_code);
        }
  }
};

const NearestCodeTable& nearest_code_table() {
  static const NearestCodeTable table;   // built on first use (thread-safe static)
  return table;
}

}  // namespace

int quantise_channel(float value, int bits, int pbit) {
  // The ideal value is rounded to the nearest 8-bit value first (the lattice is a subset of the 8-bit values,
  // so this changes the chosen code only when `value` is within 0.5 of a midpoint between two codes).
  const float clamped = value < 0.0f ? 0.0f : (value > 255.0f ? 255.0f : value);
  return nearest_code_table().nearest[bits][pbit + 1][static_cast<int>(clamped + 0.5f)];
}

QuantisedEndpoints quantise_endpoints(const float ideal[2][4], const EndpointLattice& lattice, int p0, int p1) {
  QuantisedEndpoints result;
  const bool has_pbit = lattice.pbit != PbitKind::none;
  if (lattice.pbit == PbitKind::shared) p1 = p0;   // one bit for the subset
  const int pbit_of[2] = {has_pbit ? p0 : -1, has_pbit ? p1 : -1};
  for (int endpoint = 0; endpoint < 2; ++endpoint) {
    result.pbits[endpoint] = static_cast<std::uint8_t>(has_pbit ? pbit_of[endpoint] : 0);
    for (int lane = 0; lane < 4; ++lane) {
      const int bits = lattice.lane_bits[lane];
      if (bits == 0) {   // lane not stored (alpha of modes 0-3): decodes to 255
        result.codes[endpoint][lane] = 0;
        result.expanded[endpoint][lane] = 255;
        continue;
      }
      const int code = quantise_channel(ideal[endpoint][lane], bits, pbit_of[endpoint]);
      result.codes[endpoint][lane] = static_cast<std::uint8_t>(code);
      result.expanded[endpoint][lane] = expand_code(code, bits, pbit_of[endpoint]);
    }
  }
  return result;
}

namespace {

// Weighted squared distance between an ideal endpoint and its quantisation with P-bit `pbit`.
float endpoint_quantisation_error(const float ideal[4], const EndpointLattice& lattice, const float weights[4],
                                  int pbit) {
  float error = 0.0f;
  for (int lane = 0; lane < 4; ++lane) {
    const int bits = lattice.lane_bits[lane];
    if (bits == 0) continue;
    const float difference =
        static_cast<float>(expand_code(quantise_channel(ideal[lane], bits, pbit), bits, pbit)) - ideal[lane];
    error += weights[lane] * difference * difference;
  }
  return error;
}

}  // namespace

int pbit_candidates(const float ideal[2][4], const EndpointLattice& lattice, const float weights[4], bool search_all,
                    int (&combos)[4][2]) {
  switch (lattice.pbit) {
    case PbitKind::none:
      combos[0][0] = combos[0][1] = 0;
      return 1;
    case PbitKind::shared:
      if (lattice.force_pbit_one) { combos[0][0] = combos[0][1] = 1; return 1; }
      if (search_all) {
        combos[0][0] = combos[0][1] = 0;
        combos[1][0] = combos[1][1] = 1;
        return 2;
      } else {
        const float error0 = endpoint_quantisation_error(ideal[0], lattice, weights, 0) +
                             endpoint_quantisation_error(ideal[1], lattice, weights, 0);
        const float error1 = endpoint_quantisation_error(ideal[0], lattice, weights, 1) +
                             endpoint_quantisation_error(ideal[1], lattice, weights, 1);
        combos[0][0] = combos[0][1] = error1 < error0 ? 1 : 0;
        return 1;
      }
    case PbitKind::per_endpoint:
      if (lattice.force_pbit_one) { combos[0][0] = combos[0][1] = 1; return 1; }
      if (search_all) {
        for (int i = 0; i < 4; ++i) {
          combos[i][0] = i & 1;
          combos[i][1] = i >> 1;
        }
        return 4;
      }
      for (int endpoint = 0; endpoint < 2; ++endpoint) {
        const float error0 = endpoint_quantisation_error(ideal[endpoint], lattice, weights, 0);
        const float error1 = endpoint_quantisation_error(ideal[endpoint], lattice, weights, 1);
        combos[0][endpoint] = error1 < error0 ? 1 : 0;
      }
      return 1;
  }
  return 0;
}

}  // namespace bc7
}  // namespace blocklab
