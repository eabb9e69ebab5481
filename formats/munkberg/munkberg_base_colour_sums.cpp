// The log2[RGB] chroma error through the base colours' cache (formats/munkberg/munkberg_base_colour_sums.h).
#include "formats/munkberg/munkberg_base_colour_sums.h"

#include "formats/munkberg/munkberg_chroma.h"

namespace blocklab::munkberg {

double eval_below_cached(const ChromaLogError& error, const std::array<int, kBaseCoordinateCount>& codes,
                         double bound, BaseColourSums* cache) {
  const std::array<double, kBaseCoordinateCount> x = base_code_point(codes);
  double lu[kShapeLandmarkCount], lv[kShapeLandmarkCount];
  decode_landmarks(error.shape, x.data(), lu, lv);
  const double* sums0 = cache->sums(error, 0, codes[0], codes[1], x[0], x[1], lu[0], lv[0]);
  const double* sums1 = cache->sums(error, 1, codes[2], codes[3], x[2], x[3], lu[1], lv[1]);
  return error.eval_below_given_base_sums(lu, lv, sums0, sums1, bound);
}

}  // namespace blocklab::munkberg
