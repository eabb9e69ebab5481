// Encoder of the extended-S3TC mode (formats/munkberg/ext_s3tc_block.h; Munkberg et al. 2008, section 6.1): a line
// fit (principal axis of the block's colours in the working space, extremes of the projections; and the darkest /
// brightest texel pair), endpoint quantisation, then a coordinate descent over the six endpoint codes in the block's
// log2[RGB] error with the best of the 32 palette entries per texel (the error the encoder selects modes by, §6).
#pragma once

#include "core/blocks.h"
#include "formats/munkberg/ext_s3tc_block.h"

namespace blocklab::munkberg {

struct ExtS3tcSettings {
  ExtS3tcSpace space = ExtS3tcSpace::rgb;
  int refine_passes = 4;   // coordinate-descent passes over the 6 endpoint codes (0 = quantised line fit only)
};

// Best-effort block in this mode; `error` (optional) receives its log2[RGB] block error. The result is canonical
// (anchor index[0] <= 15) and packs.
ExtS3tcParams encode_ext_s3tc(const BlockTexels& texels, const ExtS3tcSettings& settings, double* error = nullptr);

// The best index per texel for fixed endpoints (smallest log2[RGB] error of the decoded palette entry; ties keep the
// lower index) and the resulting block error. `params->index` is overwritten (not canonicalised).
double assign_ext_s3tc_indices(const BlockTexels& texels, ExtS3tcSpace space, ExtS3tcParams* params);

}  // namespace blocklab::munkberg
