// Joint code choice of the `wang` encoder (formats/wang/wang_joint_codes.h).
#include "formats/wang/wang_joint_codes.h"

#include <cmath>
#include <limits>

#include "formats/wang/wang_luminance_codec.h"
#include "formats/wang/wang_residual_codec.h"

namespace blocklab {
namespace wang {

double choose_codes_jointly(const LuminanceBlockError& luminance, const ResidualBlockError& residual,
                            BlockParams& params) {
  double part0[8], part1[8], entry[4];
  alpha_parts(luminance, params.tex0.alpha, params.tex1.alpha, part0, part1);
  residual_entries(residual, params.tex1.color, entry);
  double total = 0.0;
  for (int texel = 0; texel < 16; ++texel) {
    // Start from the texel's current codes, so ties (and equal errors) keep them.
    int best_i = params.tex0.alpha.indices[texel] & 7, best_j = params.tex1.alpha.indices[texel] & 7;
    int best_k = params.tex1.color.indices[texel] & 3;
    const double target = residual.luminance[texel];
    double best = std::abs(target - residual.reconstruct(part0[best_i] + part1[best_j], entry[best_k]));
    for (int i = 0; i < 8; ++i)
      for (int j = 0; j < 8; ++j) {
        const double base = part0[i] + part1[j];
        for (int k = 0; k < 4; ++k) {
          const double distance = std::abs(target - residual.reconstruct(base, entry[k]));
          if (distance < best) {
            best = distance;
            best_i = i;
            best_j = j;
            best_k = k;
          }
        }
      }
    params.tex0.alpha.indices[texel] = static_cast<std::uint8_t>(best_i);
    params.tex1.alpha.indices[texel] = static_cast<std::uint8_t>(best_j);
    params.tex1.color.indices[texel] = static_cast<std::uint8_t>(best_k);
    total += residual.weight[texel] * best;
  }
  return total;
}

}  // namespace wang
}  // namespace blocklab
