// The inverse-TMO lookup table and Listing 1's texel expansion (formats/banterle/itmo_lut.h; Banterle et al. 2008
// section 4.4, Listing 1).
#include "formats/banterle/itmo_lut.h"

#include <Imath/half.h>

#include <cmath>
#include <limits>

#include "core/error.h"
#include "formats/banterle/reinhard_operator.h"

namespace blocklab {

namespace {

// The peak's binade after scaling: [2^14, 2^15), two binades below half's largest finite value.
constexpr int kPeakExponent = 15;

void require_positive(double value, const char* name, const std::string& who) {
  // NaN fails both comparisons; +-inf fails the finiteness test.
  if (!(value > 0.0) || !std::isfinite(value))
    fail(who, std::string("side data '") + name + "' must be finite and > 0, got " + std::to_string(value));
}

}  // namespace

ItmoLut build_itmo_lut(double alpha, double l_white, double mean, const std::string& who) {
  require_positive(alpha, "alpha", who);
  require_positive(l_white, "l_white", who);
  require_positive(mean, "mean", who);
  const double peak = reinhard_inverse(1.0, alpha, l_white, mean);
  // The peak must be a normal double (a subnormal or zero peak makes the whole table 0) and leave float headroom.
  if (!(peak >= std::numeric_limits<double>::min()) || !(peak <= kMaxItmoPeak))
    fail(who, "side data gives an inverse-TMO peak g(1) = l_white * mean / alpha = " + std::to_string(peak) +
                  ", outside [2.2e-308, 1e30]");
  ItmoLut lut;
  int binade = 0;
  std::frexp(peak, &binade);
  lut.exponent = binade - kPeakExponent;
  for (int k = 0; k < 256; ++k) {
    const double value = std::ldexp(reinhard_inverse(static_cast<double>(k) / 255.0, alpha, l_white, mean),
                                    -lut.exponent);
    const Imath::half entry(static_cast<float>(value));   // round to nearest, ties to even
    lut.half_bits[static_cast<std::size_t>(k)] = entry.bits();
    lut.values[static_cast<std::size_t>(k)] = static_cast<float>(entry);
  }
  return lut;
}

float itmo_lookup(const ItmoLut& lut, float tone_mapped) {
  float t = tone_mapped * 255.0f;
  // Clamp to the table (the 1D texture's clamp-to-edge addressing); a NaN also lands on entry 0.
  if (!(t > 0.0f)) t = 0.0f;
  if (t > 255.0f) t = 255.0f;
  int index = static_cast<int>(t);   // t >= 0: truncation is floor
  if (index > 254) index = 254;      // t == 255 interpolates the last pair with weight 1
  const float weight = t - static_cast<float>(index);
  const float low = lut.values[static_cast<std::size_t>(index)];
  const float high = lut.values[static_cast<std::size_t>(index + 1)];
  const float value = low + (high - low) * weight;
  return std::ldexp(value, lut.exponent);
}

void itmo_decode_texel(const ItmoLut& lut, const float ldr[3], float residual, float out[3]) {
  const float luminance = banterle_luminance(ldr);
  float total = itmo_lookup(lut, luminance) + residual;
  // A negative residual larger than the reconstruction would give a negative colour: clamp to black.
  if (!(total > 0.0f)) total = 0.0f;
  if (!(luminance > 0.0f)) {
    // Black LDR texel: Listing 1 divides 0 by 0; use the grey limit so the residual still adds luminance.
    out[0] = out[1] = out[2] = total;
    return;
  }
  for (int channel = 0; channel < 3; ++channel) out[channel] = (ldr[channel] * total) / luminance;
}

}  // namespace blocklab
