// `compete`: a cross-paper mode competition at 8 bpp HDR (formats/compete/README.md). One 128-bit block whose
// prefix-coded family code (compete_layout.h) selects a BC6H two-region block (Khronos Data Format Specification,
// "BC6H", stored as is) or a block of Munkberg et al. 2008's shape modes (section 5) or section 6 modes (extended
// S3TC, DCT, two-plane), each paying two bits for the code. Every block takes the family and mode with the lowest
// log2[RGB] error (compete_encoder.h); option `families` removes families for ablations.
#pragma once

#include "formats/format.h"

namespace blocklab {

const Format& compete_format();

}  // namespace blocklab
