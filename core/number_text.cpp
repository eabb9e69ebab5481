// core/number_text.h.
#include "core/number_text.h"

#include <cstdio>

namespace blocklab {

std::string exact_number_text(double value) {
  char buffer[40];   // "-1.2345678901234567e-308" is 24 characters
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

}  // namespace blocklab
