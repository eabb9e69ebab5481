// Log-domain refinement of a tone-mapped S3TC colour block (formats/banterle/log_domain_refine.h).
#include "formats/banterle/log_domain_refine.h"

#include <cmath>

namespace blocklab {

namespace {

constexpr int kMaxPasses = 8;
constexpr float kFloor = 5.9604645e-08f;   // 2^-24, metrics/zero_rule.h

double floored_log2(float value) { return std::log2(static_cast<double>(value > kFloor ? value : kFloor)); }

struct Target {
  double log2_rgb[16][3];
};

// Error of the block with every texel on its best palette entry (indices written to `indices`).
double assign(const Target& target, const ItmoLut& lut, const Bc1Params& params, std::array<std::uint8_t, 16>& indices) {
  double endpoint0[3], endpoint1[3];
  for (int c = 0; c < 3; ++c) {
    endpoint0[c] = params.endpoints[0][c];
    endpoint1[c] = params.endpoints[1][c];
  }
  double palette[4][3];
  bc1_palette(endpoint0, endpoint1, params.mode, palette);
  double decoded_log2[4][3];
  for (int p = 0; p < 4; ++p) {
    // The decoder's float palette value (decode_bc1_params casts the exact fraction to float), then Listing 1.
    const float ldr[3] = {static_cast<float>(palette[p][0]), static_cast<float>(palette[p][1]),
                          static_cast<float>(palette[p][2])};
    float out[3];
    itmo_decode_texel(lut, ldr, 0.0f, out);
    for (int c = 0; c < 3; ++c) decoded_log2[p][c] = floored_log2(out[c]);
  }
  double total = 0.0;
  for (int texel = 0; texel < 16; ++texel) {
    int best = 0;
    double best_error = 0.0;
    for (int p = 0; p < 4; ++p) {
      double error = 0.0;
      for (int c = 0; c < 3; ++c) error += std::pow(target.log2_rgb[texel][c] - decoded_log2[p][c], 2);
      if (p == 0 || error < best_error) {   // strict: ties keep the lower index
        best = p;
        best_error = error;
      }
    }
    indices[static_cast<std::size_t>(texel)] = static_cast<std::uint8_t>(best);
    total += best_error;
  }
  return total;
}

double worst_texel(const Target& target, const ItmoLut& lut, const Bc1Params& params) {
  const BlockTexels decoded = decode_bc1_params(params);
  double worst = 0.0;
  for (int texel = 0; texel < 16; ++texel) {
    float out[3];
    itmo_decode_texel(lut, decoded.rgba[texel], 0.0f, out);
    double error = 0.0;
    for (int c = 0; c < 3; ++c) error += std::pow(target.log2_rgb[texel][c] - floored_log2(out[c]), 2);
    worst = error > worst ? error : worst;
  }
  return worst;
}

}  // namespace

double refine_color_block_log_domain(const BlockTexels& source, const ItmoLut& lut, bool bc3, Bc1Params& params) {
  Target target;
  for (int texel = 0; texel < 16; ++texel)
    for (int c = 0; c < 3; ++c) target.log2_rgb[texel][c] = floored_log2(source.rgba[texel][c]);
  double best_error = assign(target, lut, params, params.indices);
  if (worst_texel(target, lut, params) > kCatastrophicError) {
    for (int pass = 0; pass < kMaxPasses; ++pass) {
      bool moved = false;
      for (int e = 0; e < 2 && !moved; ++e)
        for (int c = 0; c < 3 && !moved; ++c)
          for (int step : {+1, -1}) {
            Bc1Params candidate = params;
            const int value = candidate.endpoints[e][c] + step;
            // Stay on the RGB565 lattice.
            if (value < 0 || value > rgb565_channel_max(c)) continue;
            candidate.endpoints[e][c] = value;
            const double error = assign(target, lut, candidate, candidate.indices);
            if (error < best_error) {
              best_error = error;
              params = candidate;
              moved = true;
              break;
            }
          }
      if (!moved) break;
    }
  }
  // Endpoint moves may have changed the packed order: restore the canonical form (same decoded texels).
  params = bc3 ? canonicalise_bc3_color(params) : canonicalise_bc1(params);
  return best_error;
}

}  // namespace blocklab
