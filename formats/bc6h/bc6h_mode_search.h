// The BC6H block encoder: mode and partition search by estimates, endpoint fit in the unquantised domain, index
// selection against the exact decoder (bc6h_decode.h), least-squares refinement. Error: weighted squared differences
// in the error domain of the `error` choice (bc6h_endpoint_fit.h: a log2 scale of the half values, or mPSNR's
// exposure-weighted gamma scale). Deterministic: no randomness, ties keep the first candidate in a fixed
// order (one-subset modes, then partitions best-estimate first, each with the two-subset modes in table order).
// A block whose error reaches 0 stops the search.
#pragma once

#include <cstdint>

#include "formats/bc6h/bc6h_endpoint_fit.h"
#include "formats/bc6h/bc6h_params.h"

namespace blocklab {
namespace bc6h {

struct EncoderSettings {
  bool mode_enabled[kModeCount] = {};   // by mode index (bc6h_tables.h)
  int partitions_to_refine = 2;         // two-subset partitions fully fitted, best estimates first (1..32)
  int modes_to_refine = 2;              // per group of modes sharing regions, the best line fits refined (1..14)
  int refine_iterations = 1;            // least-squares rounds after the line fit (0..8)
  HdrBlockError error = HdrBlockError::log2_floor;   // the block error (make_block_target's; bc6h_endpoint_fit.h)
};

struct EncodedBlock {
  Params params;
  double error = 0.0;   // sum over the 16 texels x RGB of weighted squared error-domain differences (BlockTarget)
};

EncodedBlock encode_block(const BlockTarget& block, const EncoderSettings& settings);

// The block fitted in one given mode and partition (partition ignored by one-subset modes), with the line fit and
// `refine_iterations` least-squares rounds: what encode_block compares. Exposed for tests and the block problem.
EncodedBlock encode_in_mode(const BlockTarget& block, int mode_index, int partition, int refine_iterations);

}  // namespace bc6h
}  // namespace blocklab
