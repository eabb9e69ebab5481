// Filtering of the `wang` textures (Wang et al. 2007 section 4.4 and Fig. 5, Appendix B eqs. 17-18). The GPU filters
// the fetched 8-bit channels of tex0 and tex1 and the section 3.4 shader decodes the FILTERED texel; an ideal filter
// would interpolate the decoded RGB. The two differ where the shader is not linear in the channels: the product
// t0.rgb * L of eq. 8, and for the residual ratio T the product L' T of eq. 11. Appendix B: the interpolation error of
// P = Q L is small when L1 ~ L2 or when P and L go in the same direction between the two texels (RGB vs L for
// UVW; S vs L' for T = S / L'; the paper measured 97.5 % and 76.1 % of pairs satisfying it).
//
// Bilinear filtering here: texel centres at integer coordinates, a sample at (x + fx, y + fy) with x, y the texel
// to the upper left and fx, fy in (0, 1) mixes the four texels with weights (1 - fx)(1 - fy), ...; in float on the
// fetched values (wang_shader.h steps 1-2) for the shader path, in float on RGB otherwise. Hardware filter weights
// have fewer bits; that adds the same small error to both paths.
#pragma once

#include <cstddef>
#include <vector>

#include "core/image.h"
#include "formats/format.h"
#include "formats/wang/wang_block.h"

namespace blocklab {
namespace wang {

// The texture unit's values of every texel of the image (wang_shader.h steps 1-2): 4 floats per texel, row-major.
struct FetchedTextures {
  int width = 0, height = 0;
  std::vector<float> tex0, tex1;
};
FetchedTextures fetch_textures(const EncodedTexture& texture);

// Magnified images sampled at x + offsets[i], y + offsets[j] for every texel (x, y) with x < width - 1 and
// y < height - 1: size ((width - 1) n) x ((height - 1) n), n = offsets.size(), pixel (x n + i, y n + j). Offsets in
// (0, 1). The image must be at least 2x2.
// The shader (setup) applied to the bilinearly filtered fetched channels: what the GPU renders.
Image magnify_shaded(const DecodeSetup& setup, const FetchedTextures& fetched, const std::vector<double>& offsets);
// RGB bilinearly filtered (the source image, or the per-texel decoded image): the ideal.
Image magnify_rgb(const Image& image, const std::vector<double>& offsets);

// Appendix B's condition 2 over horizontally and vertically adjacent texel pairs: the differences of P and of L
// between the two texels have the same sign or one of them is 0 (dP dL >= 0).
struct SameDirection {
  std::size_t rgb_pairs = 0, rgb_same = 0;   // P = R, G or B of the source, L its luminance (eq. 1 / eq. 10)
  std::size_t s_pairs = 0, s_same = 0;       // P = S = L - L' (eq. 5), L' the decoded eq. 4 luminance
  double rgb_fraction() const {
    return rgb_pairs ? static_cast<double>(rgb_same) / static_cast<double>(rgb_pairs) : 0.0;
  }
  double s_fraction() const { return s_pairs ? static_cast<double>(s_same) / static_cast<double>(s_pairs) : 0.0; }
};
SameDirection same_direction(const Image& source, const DecodeSetup& setup, const FetchedTextures& fetched);

}  // namespace wang
}  // namespace blocklab
