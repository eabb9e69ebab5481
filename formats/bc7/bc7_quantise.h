// Quantisation of ideal (continuous, 0..255) endpoints to a BC7 mode's endpoint lattice, including the P-bits
// (KDFS "BPTC": stored bits + optional P-bit, expanded by bit replication). P-bits are part of the error the
// encoder measures (SPECS.md 2.5 item 4, DirectXTex #92): every candidate combination is quantised and its
// expanded values are what the index assignment and the error see.
#pragma once

#include <cstdint>

namespace blocklab {
namespace bc7 {

enum class PbitKind { none, per_endpoint, shared };

// How the two endpoints of one subset are stored.
struct EndpointLattice {
  int lane_bits[4] = {0, 0, 0, 0};   // stored bits per lane (R, G, B, A) without the P-bit; 0 = lane not stored
  PbitKind pbit = PbitKind::none;
  bool force_pbit_one = false;       // opaque alpha in modes 6/7: alpha 255 needs P = 1 on both endpoints
};

struct QuantisedEndpoints {
  std::uint8_t codes[2][4] = {};     // stored codes (without P-bit); 0 for lanes not stored
  std::uint8_t pbits[2] = {};        // per endpoint (shared kind: equal)
  int expanded[2][4] = {};           // 8-bit values the decoder sees; 255 for lanes not stored
};

// Nearest stored code of `bits` bits to round(value) (value clamped to 0..255) when the P-bit `pbit` (0/1, or -1
// for none) is appended; ties go to the lower code. Table lookup.
int quantise_channel(float value, int bits, int pbit);
// 8-bit value of stored code `code` (bits wide) with P-bit `pbit` (-1 = none).
int expand_code(int code, int bits, int pbit);

// Quantises both endpoints with the given P-bits (ignored for PbitKind::none; for `shared` p0 is used for both).
QuantisedEndpoints quantise_endpoints(const float ideal[2][4], const EndpointLattice& lattice, int p0, int p1);

// The P-bit combinations to try: all of them (`search_all`), or one chosen per endpoint (per subset for
// `shared`) by the smaller weighted quantisation error of the endpoint itself. Returns the count (1, 2 or 4) and
// fills combos[i] = {p0, p1}. force_pbit_one gives the single combination {1, 1}.
int pbit_candidates(const float ideal[2][4], const EndpointLattice& lattice, const float weights[4], bool search_all,
                    int (&combos)[4][2]);

}  // namespace bc7
}  // namespace blocklab
