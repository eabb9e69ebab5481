// SplitMix64 streams and portable draws (solvers/seeding.h).
#include "solvers/seeding.h"

#include <cmath>

namespace blocklab {

std::uint64_t splitmix64_next(std::uint64_t& state) {
  state += 0x9e3779b97f4a7c15ULL;   // the golden-ratio increment (odd, so the state visits all 2^64 values)
  std::uint64_t z = state;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

std::uint64_t derive_stream_seed(std::uint64_t global_seed, std::uint64_t block_index) {
  std::uint64_t index_state = block_index;
  std::uint64_t state = global_seed ^ splitmix64_next(index_state);
  return splitmix64_next(state);
}

double RandomStream::uniform01() {
  // 53 random mantissa bits: exact in a double, never 1.0.
  return static_cast<double>(next_word() >> 11) * 0x1.0p-53;
}

std::uint64_t RandomStream::uniform_index(std::uint64_t bound) {
  if (bound <= 1) return 0;   // one choice (or a degenerate bound): nothing to draw
  // Lemire, "Fast random integer generation in an interval" (ACM TOMACS 2019): the high word of word * bound is
  // uniform once the low word is outside the biased zone [0, 2^64 mod bound).
  const std::uint64_t threshold = (0 - bound) % bound;   // 2^64 mod bound
  for (;;) {
    const unsigned __int128 product = static_cast<unsigned __int128>(next_word()) * bound;
    if (static_cast<std::uint64_t>(product) >= threshold) return static_cast<std::uint64_t>(product >> 64);
  }
}

double RandomStream::normal() {
  if (has_spare_normal_) {
    has_spare_normal_ = false;
    return spare_normal_;
  }
  // Marsaglia & Bray polar method: a uniform point in the unit disc (rejection), then two independent deviates.
  for (;;) {
    const double u = 2.0 * uniform01() - 1.0;
    const double v = 2.0 * uniform01() - 1.0;
    const double s = u * u + v * v;
    // s == 0 would take log(0); s >= 1 is outside the disc. Both are rejected.
    if (s > 0.0 && s < 1.0) {
      const double factor = std::sqrt(-2.0 * std::log(s) / s);
      spare_normal_ = v * factor;
      has_spare_normal_ = true;
      return u * factor;
    }
  }
}

}  // namespace blocklab
