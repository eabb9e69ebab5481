// The block error an HDR encoder minimises, as a choice (option `error` of bc6h, bc6h_sf and munkberg):
//
//   log2_floor      squared differences of log2 values, every R, G, B value raised to 2^-24 first: the log2[RGB]
//                   metric under its default zero rule (metrics/zero_rule.h, "floor").
//   log2_skip       the same, but a channel value whose source is <= 0 weighs 0: log2[RGB] under the skip rule
//                   (metrics/zero_rule.h, "skip": a value where either image is <= 0 is left out; a source zero is
//                   left out whatever the encoder decodes, so it must not cost anything).
//   mpsnr_weighted  an exposure-weighted squared error that tracks mPSNR (SPECS.md 1b, metrics/mpsnr.cpp):
//
// Derivation of mpsnr_weighted. mPSNR's MSE sums, over the stops c = -10..+10 (the metric's defaults) and the R, G, B
// values x of every pixel, (T_c(x') - T_c(x))^2 with the tone curve (metrics/exposure_tonemap.h)
//     T_c(x) = min(255, 255 s_c g(x)),   g(x) = x^(1/2.2),   s_c = 2^(c/2.2).
// In the gamma domain g the curve is linear with slope dT_c/dg = 255 s_c below its clamp and 0 above it (where
// s_c g(x) >= 1). So, when x' and x lie on the same side of each stop's clamp, EXACTLY
//     sum_c (T_c(x') - T_c(x))^2 = W(x) (g(x') - g(x))^2,   W(x) = sum_{c: s_c g(x) < 1} (255 s_c)^2,
// the sum over the stops of the squared derivative of the tone curve, zero where the curve is clamped. W falls in
// steps as x brightens (each stop saturating drops its term) and is largest for dark values, whose every exposure
// shows them; a value that saturates at every stop (x >= 2^10) weighs 0. Across a clamp the true error is smaller
// (x' above) or larger (x' below) than W (g' - g)^2; codecs' errors are small next to a stop (a factor 2^(1/2.2))
// within a block's range of values, and a block spanning several octaves crosses many. So an encoder that can
// afford it scores a candidate x' exactly, stop by stop (mpsnr_stop_error: with k(g) the number of unclamped stops,
// W on the stops both leave unclamped plus sum (1 - s_c g)^2 over the stops only one leaves unclamped, from prefix
// sums of s_c and s_c^2), and uses W only as the least-squares weight of its endpoint fits (bc6h); one whose
// error domain is log2 x (munkberg) uses the chain rule dg/dlog2 x = g(x) ln2 / 2.2, i.e. weight
//     W_log2(x) = W(x) (g(x) ln 2 / 2.2)^2   on   (log2 x' - log2 x)^2,
// which agrees to first order. The constant 255^2 is left out (only comparisons within a block matter).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace blocklab {

enum class HdrBlockError { log2_floor, log2_skip, mpsnr_weighted };

// The option's choices, name and value, in the order the option table lists them.
const std::vector<std::pair<std::string, HdrBlockError>>& hdr_block_error_choices();
// One line for the option table's help text.
const char* hdr_block_error_help();

// The mPSNR stops the weight sums over: the metric's defaults (metrics/mpsnr.cpp, astcenc's -mpsnr -10 10).
inline constexpr int kMpsnrWeightFirstStop = -10;
inline constexpr int kMpsnrWeightLastStop = 10;

// g(x) = x^(1/2.2); 0 for x <= 0 or NaN (as the metric).
double mpsnr_gamma(double x);
// W(x) / 255^2 = sum over the unclamped stops of s_c^2 (see above); 0 where every stop clamps.
double mpsnr_gamma_weight(double x);
// k(g): how many stops leave g unclamped (s_c g < 1; they are the darkest exposures, the first k of the range).
int mpsnr_unclamped_stops(double gamma);

// The stops' scales s_c = 2^(c/2.2), darkest exposure first, and prefix sums of s_c and s_c^2 (tabulated once).
struct MpsnrStopSums {
  static constexpr int kStops = kMpsnrWeightLastStop - kMpsnrWeightFirstStop + 1;
  double scale[kStops] = {};
  double sum[kStops + 1] = {};           // sum of s_c over the first k stops
  double sum_squares[kStops + 1] = {};   // sum of s_c^2 over the first k stops
};
const MpsnrStopSums& mpsnr_stop_sums();

// Exactly sum over the stops of (min(1, s_c g_test) - min(1, s_c g_reference))^2 (mPSNR's per-value error / 255^2),
// given each value's g and k(g): sum_squares[low] (g_test - g_reference)^2 on the stops both leave unclamped plus,
// on the stops [low, high) only the darker value (gamma g) leaves unclamped, sum (1 - s_c g)^2
// = (high - low) - 2 g (sum[high] - sum[low]) + g^2 (sum_squares[high] - sum_squares[low]) (0 when low = high).
// Branch-free, for the inner loops of encoders.
inline double mpsnr_stop_error(const MpsnrStopSums& sums, double gamma_test, int unclamped_test,
                               double gamma_reference, int unclamped_reference) {
  const double d = gamma_test - gamma_reference;
  const bool test_darker = unclamped_test > unclamped_reference;
  const int low = test_darker ? unclamped_reference : unclamped_test;
  const int high = test_darker ? unclamped_test : unclamped_reference;
  const double g = test_darker ? gamma_test : gamma_reference;
  const double crossing = static_cast<double>(high - low) - 2.0 * g * (sums.sum[high] - sums.sum[low]) +
                          g * g * (sums.sum_squares[high] - sums.sum_squares[low]);
  return sums.sum_squares[low] * (d * d) + (crossing > 0.0 ? crossing : 0.0);
}
inline double mpsnr_stop_error(double gamma_test, int unclamped_test, double gamma_reference, int unclamped_reference) {
  return mpsnr_stop_error(mpsnr_stop_sums(), gamma_test, unclamped_test, gamma_reference, unclamped_reference);
}
// W_log2(x) / 255^2: the weight of a squared log2 difference at source value x (0 for x <= 0).
double mpsnr_log2_weight(double x);

// The weight of a squared error-domain difference at source value x under `error`, for an encoder whose error
// domain is log2 (floor 2^-24): 1 (log2_floor), 0 for x <= 0 else 1 (log2_skip), mpsnr_log2_weight (mpsnr_weighted).
double log2_domain_weight(HdrBlockError error, double x);

}  // namespace blocklab
