// Text form of blocklab::Interval (core/interval.h), used in error messages and test failure output.
#include "core/interval.h"

#include <cstdio>

namespace blocklab {

std::string to_string(const Interval& x) {
  if (is_empty(x)) return "empty";
  char buffer[96];
  // 17 significant digits round-trip a double, so outward-widened bounds stay visible in the text.
  std::snprintf(buffer, sizeof buffer, "[%.17g, %.17g]", x.lower(), x.upper());
  return buffer;
}

}  // namespace blocklab
