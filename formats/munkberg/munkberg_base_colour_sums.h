// A cache of the base colours' shares of the log2[RGB] chroma error (formats/munkberg/munkberg_log_error.h) for one
// block and mode: ChromaLogError::landmark_group_sums at the lattice point of a base-colour code pair.
//
// Why it pays: landmark 0 decodes to base colour 0 exactly, and landmark 1 (B0 + (B1 - B0)) to base colour 1 unless
// that subtraction rounds. Their per-group sums depend on the decoded (u, v) only, not on the shape. The global search
// evaluates ~80 candidates per mode whose ~22 distinct base colours repeat across shapes and correspondences, and a
// radius-1 polish pass moves each base colour over only 9 positions. So most evaluations need only landmarks 2 and
// 3's sums (ChromaLogError::eval_below_given_base_sums), which are bit-identical to eval_below's.
#pragma once

#include <array>

#include "formats/munkberg/munkberg_log_error.h"

namespace blocklab::munkberg {

class BaseColourSums {
 public:
  BaseColourSums() { clear(); }
  // Empties the table (for another block or mode).
  void clear() { key_.fill(kEmpty); }

  // Landmark `landmark`'s (0 or 1) group sums in `error` (any shape: the sums do not depend on it; the mode and
  // targets must be those of every earlier call) for the decoded landmark (u, v) of a candidate whose base colour
  // `landmark` has codes (code_u, code_v) and lattice point (base_u, base_v). Cached by code pair when the landmark
  // decodes to that lattice point; computed afresh otherwise (or when the table is full). The pointer is valid until
  // the next call for the same landmark.
  const double* sums(const ChromaLogError& error, int landmark, int code_u, int code_v, double base_u, double base_v,
                     double u, double v) {
    double* fresh = fresh_[static_cast<std::size_t>(landmark)].data();
    if (!(u == base_u && v == base_v)) {   // landmark 1 off its base colour (a rounded B0 + (B1 - B0))
      error.landmark_group_sums(u, v, fresh);
      return fresh;
    }
    const int key = code_u * (kBaseCoordinateMax + 1) + code_v;
    // Open addressing with linear probing; a multiplicative hash spreads neighbouring codes.
    std::size_t slot = (static_cast<std::size_t>(key) * 2654435761u >> 8) % kSlots;
    for (int probe = 0; probe < kMaxProbes; ++probe, slot = (slot + 1) % kSlots) {
      if (key_[slot] == key) return sums_[slot].data();
      if (key_[slot] == kEmpty) {
        key_[slot] = key;
        lattice_group_sums(error, landmark, code_u, code_v, u, v, sums_[slot].data());
        return sums_[slot].data();
      }
    }
    lattice_group_sums(error, landmark, code_u, code_v, u, v, fresh);   // crowded neighbourhood: not cached
    return fresh;
  }

 private:
  // error.landmark_group_sums(u, v, sums) for a landmark at its base colour's lattice point (u, v) (codes code_u,
  // code_v): the same sums, with log2 of the R and B factors (v and u) from a table of every lattice point's log2.
  static void lattice_group_sums(const ChromaLogError& error, int landmark, int code_u, int code_v, double u, double v,
                                 double sums[kTexels]);

  static constexpr int kEmpty = -1;
  static constexpr std::size_t kSlots = 256;
  static constexpr int kMaxProbes = 8;
  std::array<int, kSlots> key_;
  std::array<std::array<double, kTexels>, kSlots> sums_;
  std::array<std::array<double, kTexels>, 2> fresh_;
};

// ChromaLogError::eval_below at base-colour codes through the cache: the same value below `bound`, bit for bit, and
// a value >= bound otherwise.
double eval_below_cached(const ChromaLogError& error, const std::array<int, kBaseCoordinateCount>& codes,
                         double bound, BaseColourSums* cache);

}  // namespace blocklab::munkberg
