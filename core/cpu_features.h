// Instruction-set features of the running CPU, for kernels that have a wider path besides the portable one. Every
// such kernel gives the same results on every path (or, for a screen whose answer is proven either way, the same
// final answer), so the choice changes speed only.
#pragma once

#if defined(__x86_64__) && defined(__GNUC__)
#define BLOCKLAB_HAS_AVX2_PATHS 1   // x86-64 with GCC / Clang: AVX2 kernels compiled with target attributes
#else
#define BLOCKLAB_HAS_AVX2_PATHS 0
#endif

namespace blocklab {

// True when the CPU runs AVX2 (checked once); always false where no AVX2 path is compiled.
inline bool cpu_has_avx2() {
#if BLOCKLAB_HAS_AVX2_PATHS
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
#else
  return false;
#endif
}

}  // namespace blocklab
