// The per-block BC7 encoder: mode and partition search (KDFS "BPTC" modes; pipeline in formats/bc7/README.md).
//
// For each enabled mode: partitioned modes rank their partitions by the PCA line-error estimate
// (bc7_partition_estimate.h) and fit the best `partitions_to_refine`; modes 4/5 try rotations (and mode 4 both
// index selections); every subset is fitted by bc7_endpoint_fit.h; the candidate's error is measured on the
// output of the real decoder (decode<T>), and the best block under the weighted squared error is kept.
// Alpha: a block whose 16 alpha values are all 255 is "opaque" and must decode to alpha 255 exactly (modes 0-3 do
// by construction, modes 4/5 store 255 exactly, modes 6/7 are restricted to P-bit 1) and tries `mode_enabled`;
// other blocks try `alpha_mode_enabled` (only modes 4-7 count; mode 6 when none is enabled).
#pragma once

#include <cstdint>

#include "formats/bc7/bc7_params.h"

namespace blocklab {
namespace bc7 {

struct EncoderSettings {
  bool mode_enabled[kModeCount] = {true, true, true, true, true, true, true, true};   // opaque blocks
  bool alpha_mode_enabled[kModeCount] = {false, false, false, false, true, true, true, true};   // others (4-7)
  int partitions_to_refine = 4;    // partitions fitted per partitioned mode, best estimates first
  int partition_candidates = 0;    // partitions re-ranked by the palette estimate (<= partitions_to_refine: none)
  double three_subset_threshold = 0;  // modes 0/2 tried only if the best weighted SSE so far is at least this
  int refine_iterations = 2;       // least-squares rounds per subset fit
  bool pbit_search = true;         // try every P-bit combination (else the per-endpoint nearest choice)
  bool rotation_search = false;    // modes 4/5: try rotations 1-3 as well as 0
  int polish_passes = 0;           // lattice polish passes per subset fit (bc7_endpoint_polish.h)
  float weights[4] = {1, 1, 1, 1}; // per-channel error weights R, G, B, A
};

// Encodes one block of 8-bit RGBA texels (texel i = x + 4y).
Params encode_block(const std::uint8_t (&rgba)[kTexels][4], const EncoderSettings& settings);

// Weighted squared error sum_i sum_c w_c (decoded - original)^2 of `params` decoded by decode<T>.
double block_error(const Params& params, const std::uint8_t (&rgba)[kTexels][4], const float weights[4]);

}  // namespace bc7
}  // namespace blocklab
