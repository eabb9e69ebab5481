// PU21 encoding, SPECS.md section 1c (see pu21.h for the formula and its source).
#include "metrics/pu21.h"

#include <cmath>

namespace blocklab {

namespace {
constexpr Pu21Parameters kBanding = {1.070275272, 0.4088273932, 0.153224308, 0.2520326168,
                                     1.063512885, 1.14115047,   521.4527484};
constexpr Pu21Parameters kBandingGlare = {0.353487901,  0.3734658629,  8.277049286e-05, 0.9062562627,
                                          0.09150303166, 0.9099517204, 596.3148142};
constexpr Pu21Parameters kPeaks = {1.043882782, 0.6459495343, 0.3194584211, 0.374025247,
                                   1.114783422, 1.095360363,  384.9217577};
constexpr Pu21Parameters kPeaksGlare = {816.885024,    1479.463946, 0.001253215609, 0.9329636822,
                                        0.06746643971, 1.573435413, 419.6006374};
}  // namespace

const Pu21Parameters& pu21_parameters(Pu21Type type) {
  switch (type) {
    case Pu21Type::banding: return kBanding;
    case Pu21Type::banding_glare: return kBandingGlare;
    case Pu21Type::peaks: return kPeaks;
    case Pu21Type::peaks_glare: return kPeaksGlare;
  }
  return kBandingGlare;   // unreachable: every enumerator is handled above
}

std::string to_string(Pu21Type type) {
  switch (type) {
    case Pu21Type::banding: return "banding";
    case Pu21Type::banding_glare: return "banding_glare";
    case Pu21Type::peaks: return "peaks";
    case Pu21Type::peaks_glare: return "peaks_glare";
  }
  return "banding_glare";   // unreachable
}

double pu21_encode(double luminance, Pu21Type type) {
  const Pu21Parameters& p = pu21_parameters(type);
  // Outside the encoder's range the value is clamped (the reference encoder does the same); NaN is not ordered, so
  // it is sent to the minimum explicitly (std::clamp would pass it through).
  double y = std::isnan(luminance) ? kPu21MinLuminance : luminance;
  y = y < kPu21MinLuminance ? kPu21MinLuminance : (y > kPu21MaxLuminance ? kPu21MaxLuminance : y);
  const double y_p4 = std::pow(y, p[3]);
  return p[6] * (std::pow((p[0] + p[1] * y_p4) / (1.0 + p[2] * y_p4), p[4]) - p[5]);
}

}  // namespace blocklab
