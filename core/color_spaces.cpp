// YCoCg-R lossless integer lifting (Malvar & Sullivan, JVT-I014, 2003); see core/color_spaces.h.
#include "core/color_spaces.h"

namespace blocklab {

// The lifting steps need `x >> 1` to be floor(x / 2) for negative x too (arithmetic shift). C++17 leaves right
// shifts of negative values implementation-defined; GCC and Clang define them as arithmetic, and this checks it.
static_assert((-3 >> 1) == -2 && (-1 >> 1) == -1, "YCoCg-R needs an arithmetic right shift of negative integers");

YCoCgR rgb_to_ycocg_r(std::int32_t r, std::int32_t g, std::int32_t b) {
  YCoCgR out{};
  out.co = r - b;
  const std::int32_t t = b + (out.co >> 1);   // t = floor((R + B) / 2)
  out.cg = g - t;
  out.y = t + (out.cg >> 1);                  // Y = floor((G + t) / 2)
  return out;
}

Rgb<std::int32_t> ycocg_r_to_rgb(const YCoCgR& ycocg) {
  // Each step undoes one forward lifting step exactly (same floor term, opposite sign).
  Rgb<std::int32_t> out{};
  const std::int32_t t = ycocg.y - (ycocg.cg >> 1);
  out.g = ycocg.cg + t;
  out.b = t - (ycocg.co >> 1);
  out.r = out.b + ycocg.co;
  return out;
}

}  // namespace blocklab
