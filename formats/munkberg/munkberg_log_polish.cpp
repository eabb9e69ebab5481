// Section 7.1's lattice polish of the base colours in the block's log2[RGB] reconstruction error (Munkberg et al.
// 2008: "we search in a small radius of quantized values around each base point to minimize the mean square error
// for the reconstructed chrominance block"), specialised for ChromaLogError (formats/munkberg/munkberg_log_error.h):
// the searches of lattice_polish (its radius-1 full neighbourhood, and its coordinate descent) with exact shortcuts
// only.
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <memory>

#include "formats/munkberg/munkberg_base_colour_sums.h"
#include "formats/munkberg/munkberg_chroma.h"
#include "formats/munkberg/munkberg_log_error.h"

namespace blocklab::munkberg {

namespace {

// The caller's cache (one per block and mode, shared with the candidate evaluation), or else a cache of this polish.
BaseColourSums* cache_or_own(BaseColourSums* cache, std::unique_ptr<BaseColourSums>& own_cache) {
  if (cache != nullptr) return cache;
  own_cache = std::make_unique<BaseColourSums>();
  return own_cache.get();
}

// lattice_polish starts from the error at the start point; the caller's value is that error (or +inf / NaN when
// unknown: then it is evaluated here).
double start_error_of(const ChromaLogError& error, const std::array<int, kBaseCoordinateCount>& start,
                      double given, BaseColourSums* cache) {
  if (given == given && given != std::numeric_limits<double>::infinity()) return given;
  return eval_below_cached(error, start, std::numeric_limits<double>::infinity(), cache);
}

}  // namespace

bool polish_log_error_full(const ChromaLogError& error, int max_passes, std::array<int, kBaseCoordinateCount>* codes,
                           double* error_at_codes, BaseColourSums* cache) {
  std::unique_ptr<BaseColourSums> own_cache;
  cache = cache_or_own(cache, own_cache);
  std::array<int, kBaseCoordinateCount> incumbent = *codes;
  double best = start_error_of(error, incumbent, *error_at_codes, cache);
  const double start_error = best;
  std::array<int, kBaseCoordinateCount> previous{};
  bool have_previous = false;
  bool improved = true;
  for (int pass = 0; improved && pass < max_passes; ++pass) {
    improved = false;
    const std::array<int, kBaseCoordinateCount> centre = incumbent;
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
            const double e = eval_below_cached(error, index, best, cache);
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

bool polish_log_error_coordinate(const ChromaLogError& error, int radius, int max_passes,
                                 std::array<int, kBaseCoordinateCount>* codes, double* error_at_codes,
                                 BaseColourSums* cache) {
  std::unique_ptr<BaseColourSums> own_cache;
  cache = cache_or_own(cache, own_cache);
  constexpr double kNoBound = std::numeric_limits<double>::infinity();
  // lattice_polish's incumbent: the start's error (a NaN start is no incumbent yet).
  std::array<int, kBaseCoordinateCount> incumbent = *codes;
  double best = start_error_of(error, incumbent, *error_at_codes, cache);
  bool found = !std::isnan(best);
  bool improved = true;
  for (int pass = 0; improved && pass < max_passes; ++pass) {
    improved = false;
    // Each coordinate in turn tries every code within +-radius of the current incumbent's (updated between
    // coordinates, not within one); clipped at the lattice ends.
    for (int p = 0; p < kBaseCoordinateCount; ++p) {
      const std::array<int, kBaseCoordinateCount> centre = incumbent;
      std::array<int, kBaseCoordinateCount> index = centre;
      for (int offset = -radius; offset <= radius; ++offset) {
        const int code = centre[static_cast<std::size_t>(p)] + offset;
        if (offset == 0 || code < 0 || code > kBaseCoordinateMax) continue;
        index[static_cast<std::size_t>(p)] = code;
        const double e = eval_below_cached(error, index, found ? best : kNoBound, cache);
        if (std::isnan(e)) continue;                // an invalid point is never the answer
        if (found && !(e < best)) continue;         // strictly lower replaces; ties keep the earlier point
        best = e;
        incumbent = index;
        found = true;
        improved = true;
      }
    }
  }
  // The polished point's error is `best` (every accepted value was below its bound, so exact); a NaN or a value not
  // below the caller's start error leaves the start.
  if (!found || !(best < *error_at_codes)) return false;
  *codes = incumbent;
  *error_at_codes = best;
  return true;
}

}  // namespace blocklab::munkberg
