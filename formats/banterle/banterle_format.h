// `banterle`: Banterle, Debattista, Ledda, Chalmers, "A GPU-friendly Method for High Dynamic Range Texture
// Compression using Inverse Tone Mapping", Graphics Interface 2008. The HDR texture is tone mapped with Reinhard's
// photographic operator (eq. 1, reinhard_operator.h) whose parameters are fitted per texture (eq. 3, tmo_fit.h),
// stored as an S3TC texture, and expanded by the inverse operator through a 256-entry half-float table (eq. 2,
// section 4.4, Listing 1; itmo_lut.h).
//   bpp 4   BC1 block (8 bytes): the tone-mapped RGB (formats/common/s3tc_color_fit.h, 3-colour mode allowed).
//   bpp 8   BC3 block (16 bytes): the tone-mapped RGB in the colour half (4-colour only) and the additive luminance
//           residual of eq. 4 quantised linearly in the alpha half (luminance_residual.h, formats/bc4 encoder).
// Side data: banterle_side_data.h. Options, decisions and measurements: formats/banterle/README.md.
//
// Options: bpp = 4 | 8; mean = geometric | harmonic (L_H of eq. 1, SPECS.md section 3); fit = none | coeff_search |
// nlopt | ceres_lm | ceres_lm_raw (tmo_fit.h); fit_options = "key=value, ..." for the fit's solver (tmo_fit.h, the
// spelling of the BC formats' solver_options); search = fast | default | exhaustive (the S3TC endpoint
// search of the colour and alpha blocks). The decoded image is RGB (alpha 1; a 4-channel source decodes as 3).
#pragma once

#include <string>

#include "core/image.h"
#include "formats/banterle/reinhard_estimate.h"
#include "formats/banterle/tmo_fit.h"
#include "formats/format.h"

namespace blocklab {

const Format& banterle_format();

// Block modes: the BC1 mode of a 4 bpp block, or 2 + the BC3 alpha mode of an 8 bpp block.
enum class BanterleMode : std::uint8_t { four_color = 0, three_color = 1, eight_alpha = 2, six_alpha = 3 };

// Section 3.1 as the encoder runs it: the Reinhard 2002 estimate (option `mean`) and the eq. 3 fit (options `fit`
// etc.) on the image's luminance. `options` must be resolved (resolve_format_options on banterle_format()).
TmoFitResult banterle_fit_tmo(const Image& image, const FormatOptions& options);

// The tone-mapped LDR image the S3TC encoder sees (eq. 1): RGB' = RGB * f(L) / L (0 where L <= 0), alpha 1; values
// above 1 are left for the encoder to clamp.
Image banterle_tone_map(const Image& image, const ReinhardParameters& parameters);

}  // namespace blocklab
