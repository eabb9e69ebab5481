// `bc7`: BC7 / BPTC unorm (Khronos Data Format Specification, "BPTC"; SPECS.md 2.3), 8 bpp, 16-byte blocks, all
// eight modes. LDR: image values are 8-bit code values scaled to [0, 1] (PNG convention of core/image.h); the
// encoder clamps to [0, 1] and rounds to the nearest code, the decoder returns code / 255.
// Files of this folder: bc7_tables (constants), bc7_params + bc7_pack (symbolic block <-> bytes), bc7_decode
// (templated decode<T>), bc7_reference_decode (spec-literal oracle), bc7_quantise (endpoints + P-bits),
// bc7_endpoint_fit (PCA + least squares), bc7_partition_estimate, bc7_mode_search, bc7_presets, bc7_endpoint_problem
// (the subset fit as a core Problem). Decisions: formats/bc7/README.md.
#pragma once

#include "formats/format.h"

namespace blocklab {

// The registry entry.
const Format& bc7_format();

}  // namespace blocklab
