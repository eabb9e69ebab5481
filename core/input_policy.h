// The one input policy for values a texture codec cannot store: NaN, +-Inf and negative channel values.
// It is applied once, right after loading, and recorded with every result (astc-encoder #649: strip non-finite
// values on entry, never in the hot loop).
//   error : the first offending value stops the run with "<file>: pixel (x, y) channel c is <value>".
//   clamp : NaN -> 0, -Inf -> 0, negative -> 0, +Inf -> 65504 (largest finite half: every HDR format here
//           stores at most fp16 range).  (default)
//   zero  : every offending value (NaN, +-Inf, negative) -> 0.
// Alpha is treated like colour.
#pragma once

#include <cstddef>
#include <string>

#include "core/image.h"

namespace blocklab {

enum class InputPolicy { error, clamp, zero };

struct InputReport {
  std::size_t nan_count = 0;
  std::size_t positive_inf_count = 0;
  std::size_t negative_inf_count = 0;
  std::size_t negative_count = 0;
  std::size_t changed_count() const { return nan_count + positive_inf_count + negative_inf_count + negative_count; }
};

InputPolicy input_policy_from_string(const std::string& name);   // throws Error listing the valid names
std::string to_string(InputPolicy policy);

// Applies `policy` in place and counts what it found. `source` names the image in error messages.
InputReport apply_input_policy(Image& image, InputPolicy policy, const std::string& source);

}  // namespace blocklab
