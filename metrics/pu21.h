// PU21 perceptually uniform encoding (Mantiuk & Azimi, "PU21: A novel perceptually uniform encoding for adapting
// existing quality metrics for HDR", PCS 2021, doi 10.1109/PCS50896.2021.9477471), SPECS.md section 1c:
//     Y = clamp(Y, 0.005, 10000)   (absolute luminance, cd/m^2)
//     V = p7 * ( ((p1 + p2 Y^p4) / (1 + p3 Y^p4))^p5 - p6 )
// Parameter sets as published in gfxdisp/pu21 matlab/pu21_encoder.m ("updated on 06/02/2020"); the default and
// recommended one is banding_glare. Test vectors (banding_glare): V(0.005) = 0.0, V(1) = 36.5439,
// V(100) = 256.3839, V(10000) = 595.3939.
#pragma once

#include <array>
#include <string>

namespace blocklab {

enum class Pu21Type { banding, banding_glare, peaks, peaks_glare };

inline constexpr double kPu21MinLuminance = 0.005;     // cd/m^2, lower clamp of the encoder
inline constexpr double kPu21MaxLuminance = 10000.0;   // cd/m^2, upper clamp of the encoder

using Pu21Parameters = std::array<double, 7>;           // p1 .. p7

const Pu21Parameters& pu21_parameters(Pu21Type type);
std::string to_string(Pu21Type type);

// PU21 value of an absolute luminance in cd/m^2 (clamped to [0.005, 10000]; NaN is treated as the minimum).
double pu21_encode(double luminance, Pu21Type type = Pu21Type::banding_glare);

}  // namespace blocklab
