// Section 7.1's lattice polish of the base colours in the block's log2[RGB] reconstruction error (Munkberg et al.
// 2008: "we search in a small radius of quantized values around each base point to minimize the mean square error
// for the reconstructed chrominance block"), specialised for ChromaLogError (formats/munkberg/munkberg_log_error.h):
// the search of lattice_polish's radius-1 full neighbourhood with exact shortcuts only.
#include <array>
#include <cstdlib>
#include <limits>

#include "formats/munkberg/munkberg_chroma.h"
#include "formats/munkberg/munkberg_log_error.h"

namespace blocklab::munkberg {

bool polish_log_error_full(const ChromaLogError& error, int max_passes, std::array<int, kBaseCoordinateCount>* codes,
                           double* error_at_codes) {
  std::array<int, kBaseCoordinateCount> incumbent = *codes;
  // lattice_polish starts from the error at the start point; the caller's value is that error (or +inf / NaN when
  // unknown: then it is evaluated here).
  double best = *error_at_codes;
  if (!(best == best) || best == std::numeric_limits<double>::infinity())
    best = error.eval_below(base_code_point(incumbent).data(), std::numeric_limits<double>::infinity());
  const double start_error = best;
  std::array<int, kBaseCoordinateCount> previous{};
  bool have_previous = false;
  bool improved = true;
  for (int pass = 0; improved && pass < max_passes; ++pass) {
    improved = false;
    const std::array<int, kBaseCoordinateCount> centre = incumbent;
    // Landmarks 0 and 1's group sums per position of their base colour in this pass's neighbourhood (3 x 3 offsets
    // each), computed on first use. Landmark 0 decodes to base colour 0 exactly; landmark 1 decodes to
    // B0 + (B1 - B0), which is B1 unless the subtraction rounds. A slot is used only when the landmark decodes to its
    // base colour exactly; any other value gets its sums computed afresh (the sums depend on the decoded value only).
    std::array<bool, 18> slot_filled{};
    std::array<std::array<double, kTexels>, 18> slot_sums;
    std::array<std::array<double, kTexels>, 2> fresh_sums;
    const auto base_sums = [&](int landmark, int offset_slot, const double* base, double u, double v) -> const double* {
      const std::size_t l = static_cast<std::size_t>(landmark);
      if (!(u == base[0] && v == base[1])) {
        error.landmark_group_sums(u, v, fresh_sums[l].data());
        return fresh_sums[l].data();
      }
      const std::size_t slot = static_cast<std::size_t>(landmark * 9 + offset_slot);
      if (!slot_filled[slot]) {
        error.landmark_group_sums(u, v, slot_sums[slot].data());
        slot_filled[slot] = true;
      }
      return slot_sums[slot].data();
    };
    for (int o0 = -1; o0 <= 1; ++o0)
      for (int o1 = -1; o1 <= 1; ++o1)
        for (int o2 = -1; o2 <= 1; ++o2)
          for (int o3 = -1; o3 <= 1; ++o3) {
            if (o0 == 0 && o1 == 0 && o2 == 0 && o3 == 0) continue;   // the centre is the incumbent's start
            const std::array<int, kBaseCoordinateCount> index = {centre[0] + o0, centre[1] + o1, centre[2] + o2,
                                                                 centre[3] + o3};
            bool inside = true, searched = have_previous;
            for (int p = 0; p < kBaseCoordinateCount; ++p) {
              const int i = index[static_cast<std::size_t>(p)];
              if (i < 0 || i > kBaseCoordinateMax) inside = false;   // clipped at the lattice ends
              if (std::abs(i - previous[static_cast<std::size_t>(p)]) > 1) searched = false;
            }
            // Searched in the previous pass: its error is >= that pass's best = the centre's error >= `best`.
            if (!inside || searched) continue;
            const std::array<double, kBaseCoordinateCount> x = base_code_point(index);
            double lu[kShapeLandmarkCount], lv[kShapeLandmarkCount];
            decode_landmarks(error.shape, x.data(), lu, lv);
            const double e = error.eval_below_given_base_sums(lu, lv, 
                                                              base_sums(0, (o0 + 1) * 3 + (o1 + 1), &x[0], lu[0], lv[0]),
                                                              base_sums(1, (o2 + 1) * 3 + (o3 + 1), &x[2], lu[1], lv[1]),
                                                              best);
            if (e < best) {   // strictly lower replaces (NaN never does); ties keep the earlier point
              best = e;
              incumbent = index;
              improved = true;
            }
          }
    previous = centre;
    have_previous = true;
  }
  if (!(best < start_error) || !(best < *error_at_codes)) return false;
  *codes = incumbent;
  *error_at_codes = best;
  return true;
}

}  // namespace blocklab::munkberg
