// The HDR block error choice and the mPSNR exposure weight (formats/common/hdr_block_error.h has the derivation).
#include "formats/common/hdr_block_error.h"

#include <algorithm>
#include <cmath>

#include "metrics/exposure_tonemap.h"

namespace blocklab {

const std::vector<std::pair<std::string, HdrBlockError>>& hdr_block_error_choices() {
  static const std::vector<std::pair<std::string, HdrBlockError>> choices = {
      {"log2_floor", HdrBlockError::log2_floor},
      {"log2_skip", HdrBlockError::log2_skip},
      {"mpsnr_weighted", HdrBlockError::mpsnr_weighted}};
  return choices;
}

const char* hdr_block_error_help() {
  return "block error the search minimises: log2_floor (squared log2 differences, values floored at 2^-24: log2[RGB] "
         "with the floor zero rule), log2_skip (the same, source zeros weigh 0: the skip rule), mpsnr_weighted "
         "(squared differences of x^(1/2.2) weighted by the sum over mPSNR's stops -10..10 of the squared slope of "
         "the unclamped tone curves)";
}

double mpsnr_gamma(double x) { return exposure_gamma_base(static_cast<float>(x)); }

const MpsnrStopSums& mpsnr_stop_sums() {
  static const MpsnrStopSums sums = [] {
    MpsnrStopSums s;
    for (int k = 0; k < MpsnrStopSums::kStops; ++k) {
      s.scale[k] = exposure_stop_scale(kMpsnrWeightFirstStop + k);
      s.sum[k + 1] = s.sum[k] + s.scale[k];
      s.sum_squares[k + 1] = s.sum_squares[k] + s.scale[k] * s.scale[k];
    }
    return s;
  }();
  return sums;
}

int mpsnr_unclamped_stops(double gamma) {
  const MpsnrStopSums& sums = mpsnr_stop_sums();
  int k = 0;
  while (k < MpsnrStopSums::kStops && sums.scale[k] * gamma < 1.0) ++k;   // this stop and every brighter one clamp
  return k;
}

double mpsnr_gamma_weight(double x) { return mpsnr_stop_sums().sum_squares[mpsnr_unclamped_stops(mpsnr_gamma(x))]; }

double mpsnr_log2_weight(double x) {
  const double slope = mpsnr_gamma(x) * std::log(2.0) / kExposureGamma;
  return mpsnr_gamma_weight(x) * slope * slope;
}

double log2_domain_weight(HdrBlockError error, double x) {
  switch (error) {
    case HdrBlockError::log2_floor: return 1.0;
    case HdrBlockError::log2_skip: return x > 0.0 ? 1.0 : 0.0;
    case HdrBlockError::mpsnr_weighted: return mpsnr_log2_weight(x);
  }
  return 1.0;
}

}  // namespace blocklab
