// Automatic parameters of Reinhard's photographic operator: E. Reinhard, "Parameter Estimation for Photographic
// Tone Reproduction", J. Graphics Tools 7(1):45-52, 2002 (SPECS.md section 3), the initial values of Banterle et
// al. 2008's fit (section 3.1: "initialized using automatic estimation as presented in [22]").
//
//   mean      L_H: geometric (log-average, Reinhard's operator: exp(mean(ln(delta + L))), delta = 1e-6 as in
//             HDR_Toolbox logMean.m) or harmonic (N / sum(1 / (delta + L)), the wording of Banterle's eq. 1);
//             SPECS.md section 3: geometric is the default, the switch is the format option `mean`.
//   alpha     0.18 * 4^((2 log2 L_H - log2 Lmin - log2 Lmax) / (log2 Lmax - log2 Lmin)), Lmin/Lmax the 1st and
//             99th percentiles of the positive luminances (HDR_Toolbox ReinhardAlpha.m / MaxQuart).
//   Lwhite    1.5 * 2^(log2 Lmax - log2 Lmin - 5), Lmin/Lmax the smallest and largest positive luminance
//             (HDR_Toolbox ReinhardWhitePoint.m).
// Luminance uses the Listing 1 weights (reinhard_operator.h) over every pixel of the image (alpha ignored).
// Percentiles: the value of rank floor(p * (n - 1)) of the sorted positive luminances (std::nth_element), so the
// estimate is deterministic and independent of the thread count.
#pragma once

#include <string>
#include <vector>

#include "core/image.h"

namespace blocklab {

enum class TmoMean { geometric, harmonic };

// "geometric" / "harmonic"; throws Error naming `who` on anything else.
TmoMean parse_tmo_mean(const std::string& text, const std::string& who);
const char* to_string(TmoMean mean);

struct ReinhardParameters {
  double alpha = 0.18;     // key value (scale factor)
  double l_white = 1.0;    // white point, in the scaled domain alpha * L / L_H
  double mean = 1.0;       // L_H
};

// Luminance of every pixel (Listing 1 weights, computed in float as the decoder does, then widened to double).
std::vector<double> banterle_luminances(const Image& image);

// The estimate for a list of luminances (negative and zero values are allowed and only enter the mean through
// delta). With no positive luminance (a black image) it returns alpha 0.18, Lwhite 1, mean 1.
ReinhardParameters estimate_reinhard_parameters(const std::vector<double>& luminances, TmoMean mean);

}  // namespace blocklab
