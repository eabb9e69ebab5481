// `bc6h` (BC6H_UF16) and `bc6h_sf` (BC6H_SF16): BPTC float (Khronos Data Format Specification, "BC6H"; Microsoft
// "BC6H format"; SPECS.md 2.4), 8 bpp, 16-byte blocks, all 14 modes, HDR RGB as half floats.
//
// Two formats rather than one with a `signed` option: the signedness changes what the bytes mean (the decoder), not
// how hard the encoder searches; DDS names them as two dxgiFormats (95, 96) and records no options, so a DDS file
// maps to a format name by itself; and a result table names the variant in its format column.
//
// Files of this folder: bc6h_tables (mode table, layouts, unquantisation), bc6h_params + bc6h_pack (symbolic block
// <-> bytes), bc6h_decode (templated fast decode), bc6h_reference_decode (spec-literal oracle), bc6h_half,
// bc6h_endpoint_fit, bc6h_partition_estimate, bc6h_mode_search, bc6h_presets, bc6h_endpoint_problem (the one-region
// endpoint fit as a core Problem), bc6h_problems. Decisions and measurements: formats/bc6h/README.md.
#pragma once

#include "formats/format.h"

namespace blocklab {

const Format& bc6h_format();      // BC6H_UF16
const Format& bc6h_sf_format();   // BC6H_SF16

}  // namespace blocklab
