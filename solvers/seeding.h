// Seeds and random numbers for the stochastic solvers (anneal, nlopt's stochastic algorithms): one documented,
// portable recipe so a (global seed, block index) pair gives the same stream on every machine and standard library.
//
// SplitMix64 (Steele, Lea, Flood, "Fast splittable pseudorandom number generators", OOPSLA 2014; the constants are
// the ones of Vigna's public-domain reference splitmix64.c): state += 0x9e3779b97f4a7c15, then the output is the
// state passed through two xor-shift-multiply rounds. It is a bijection of the 64-bit state sequence, has period
// 2^64, passes BigCrush, costs three multiplies per word and seeds in O(1), which matters when every block of an
// image gets its own stream.
//
// WHY NOT std::uniform_real_distribution / std::normal_distribution: the C++ standard fixes the raw output of the
// engines (std::mt19937_64 and friends) but NOT the algorithms of the distribution classes; libstdc++ and libc++
// turn the same engine words into different doubles (generate_canonical, the normal sampler's method). The draws
// below are written from raw 64-bit words with fixed formulas, so only IEEE arithmetic and libm's log (Box-Muller
// polar method) are involved; with the same libm the streams are bit-identical.
#pragma once

#include <cstdint>

namespace blocklab {

// One SplitMix64 step: advances `state` and returns the next output word.
std::uint64_t splitmix64_next(std::uint64_t& state);

// The seed of the random stream of block `block_index` under the run's `global_seed`: the first SplitMix64 output
// of state (global_seed XOR splitmix64(block_index)). Mixing the index first makes neighbouring blocks' streams
// unrelated, and equal (global seed, block index) pairs always give the same stream seed, whichever thread or
// order the blocks are solved in.
std::uint64_t derive_stream_seed(std::uint64_t global_seed, std::uint64_t block_index);

// A SplitMix64 stream with portable draws. Not thread-safe (each solve owns its own stream).
class RandomStream {
 public:
  explicit RandomStream(std::uint64_t seed) : state_(seed) {}

  std::uint64_t next_word() { return splitmix64_next(state_); }
  // Uniform double in [0, 1): the top 53 bits of a word times 2^-53 (every value is a multiple of 2^-53).
  double uniform01();
  // Uniform double in [lo, hi) (lo when hi == lo).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform01(); }
  // Uniform integer in [0, bound) for bound >= 1, unbiased (Lemire's multiply-shift with rejection).
  std::uint64_t uniform_index(std::uint64_t bound);
  // Standard normal deviate, Marsaglia's polar method (both deviates of a pair are used; the spare is cached).
  double normal();

 private:
  std::uint64_t state_;
  bool has_spare_normal_ = false;
  double spare_normal_ = 0.0;
};

}  // namespace blocklab
