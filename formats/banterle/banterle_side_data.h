// Per-texture side data of the `banterle` format (EncodedTexture::side_data, stored in the .blk JSON header):
//   alpha           [alpha]          Reinhard key / scale factor (eq. 1), finite > 0
//   l_white         [Lwhite]         white point in the scaled domain, finite > 0
//   mean            [L_H]            the image mean of eq. 1 (geometric or harmonic, option `mean`), finite > 0
//   residual_range  [lo, hi]         8 bpp only: the linear residual range (luminance_residual.h), finite, lo <= hi,
//                                    |lo|, |hi| <= 1e30
// Nothing else: an unknown key, a missing key, a wrong value count, or a value out of range is an Error naming the
// key and the value. alpha, l_white and mean must also give a usable inverse-TMO table (itmo_lut.h).
#pragma once

#include <string>

#include "formats/banterle/luminance_residual.h"
#include "formats/format.h"

namespace blocklab {

struct BanterleSideData {
  double alpha = 0.18;
  double l_white = 1.0;
  double mean = 1.0;
  bool has_residual = false;
  ResidualRange residual;
};

void store_banterle_side_data(const BanterleSideData& data, EncodedTexture& texture);
// Reads and validates; `with_residual` is true for bpp 8. Throws Error("<who>: side data ...").
BanterleSideData read_banterle_side_data(const EncodedTexture& texture, bool with_residual, const std::string& who);

}  // namespace blocklab
