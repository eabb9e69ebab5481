// The log2[RGB] chroma error through the base colours' cache (formats/munkberg/munkberg_base_colour_sums.h).
#include "formats/munkberg/munkberg_base_colour_sums.h"

#include <cmath>

#include "formats/munkberg/munkberg_chroma.h"

namespace blocklab::munkberg {

void BaseColourSums::lattice_group_sums(const ChromaLogError& error, int landmark, int code_u, int code_v, double u,
                                        double v, double sums[kTexels]) {
  // ChromaLogError::landmark_log_factors' R and B entries, log2 max(value, kFactorFloor), of every lattice point of
  // every base coordinate (base_code_point's values): the same std::log2 of the same doubles, computed once.
  using Log2Table = std::array<std::array<double, kBaseCoordinateMax + 1>, kBaseCoordinateCount>;
  static const Log2Table log2_of_point = [] {
    Log2Table table{};
    for (int code = 0; code <= kBaseCoordinateMax; ++code) {
      const std::array<double, kBaseCoordinateCount> point = base_code_point({code, code, code, code});
      for (std::size_t p = 0; p < kBaseCoordinateCount; ++p)
        table[p][static_cast<std::size_t>(code)] = std::log2(max(point[p], kFactorFloor));
    }
    return table;
  }();
  // Base colour `landmark` is coordinates (2 landmark, 2 landmark + 1) = (u, v), and (u, v) is their lattice point.
  const std::size_t u_coordinate = static_cast<std::size_t>(2 * landmark), v_coordinate = u_coordinate + 1;
  const double log_factor[3] = {log2_of_point[v_coordinate][static_cast<std::size_t>(code_v)],
                                std::log2(max(1.0 - u - v, kFactorFloor)),
                                log2_of_point[u_coordinate][static_cast<std::size_t>(code_u)]};
  error.group_sums_of_factors(log_factor, sums);
}

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
