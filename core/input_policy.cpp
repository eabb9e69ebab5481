// The input policy for values no texture codec can store (NaN, +-Inf, negative), applied once after loading.
// Semantics are those documented in core/input_policy.h (after astc-encoder issue #649: sanitise on entry, not in
// the hot loop):
//   error : first offending value (row-major scan, channels in R G B A order) -> Error
//           "<source>: pixel (x, y) channel c (N) is <value>";
//   clamp : NaN -> 0, -Inf -> 0, negative -> 0, +Inf -> 65504 (largest finite half);
//   zero  : NaN, +-Inf, negative -> 0.
// Which stored values are examined: the channels the source really had (Image::channels): R for luminance-only
// images (G and B are copies of R and are rewritten from the corrected R), R G B for RGB images (the stored alpha
// is the constant 1), R G B A for RGBA images (alpha is treated like colour). The counts therefore count source
// values, e.g. one NaN luminance texel counts once, not three times.
#include "core/input_policy.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "core/error.h"

namespace blocklab {
namespace {

// Largest finite IEEE-754 binary16 value: +Inf is clamped here because every HDR format in blocklab stores at
// most fp16 range.
constexpr float kLargestHalf = 65504.0f;

enum class Offence { none, nan, positive_inf, negative_inf, negative };

Offence classify(float value) {
  if (std::isnan(value)) return Offence::nan;
  if (std::isinf(value)) return value > 0.0f ? Offence::positive_inf : Offence::negative_inf;
  // -0.0 compares equal to 0 and is not counted: it is a valid stored zero in every format.
  if (value < 0.0f) return Offence::negative;
  return Offence::none;
}

std::string describe(float value) {
  if (std::isnan(value)) return "NaN";
  if (std::isinf(value)) return value > 0.0f ? "+Inf" : "-Inf";
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", static_cast<double>(value));
  return text;
}

}  // namespace

InputPolicy input_policy_from_string(const std::string& name) {
  if (name == "error") return InputPolicy::error;
  if (name == "clamp") return InputPolicy::clamp;
  if (name == "zero") return InputPolicy::zero;
  fail("input_policy", "unknown input policy \"" + name + "\" (valid: error, clamp, zero)");
}

std::string to_string(InputPolicy policy) {
  switch (policy) {
    case InputPolicy::error: return "error";
    case InputPolicy::clamp: return "clamp";
    case InputPolicy::zero: return "zero";
  }
  return "unknown";
}

InputReport apply_input_policy(Image& image, InputPolicy policy, const std::string& source) {
  static const char* const kChannelNames[4] = {"R", "G", "B", "A"};
  const bool luminance_only = image.channels == 1;
  const int examined_channels = image.channels == 4 ? 4 : (luminance_only ? 1 : 3);
  InputReport report;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      float* texel = image.texel(x, y);
      bool changed = false;
      for (int c = 0; c < examined_channels; ++c) {
        const Offence offence = classify(texel[c]);
        if (offence == Offence::none) continue;
        if (policy == InputPolicy::error) {
          fail(source, "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") channel " + std::to_string(c) +
                           " (" + kChannelNames[c] + ") is " + describe(texel[c]));
        }
        switch (offence) {
          case Offence::nan: ++report.nan_count; break;
          case Offence::positive_inf: ++report.positive_inf_count; break;
          case Offence::negative_inf: ++report.negative_inf_count; break;
          case Offence::negative: ++report.negative_count; break;
          case Offence::none: break;
        }
        // clamp keeps +Inf as the largest half; every other offence (and everything under zero) becomes 0.
        texel[c] = (policy == InputPolicy::clamp && offence == Offence::positive_inf) ? kLargestHalf : 0.0f;
        changed = true;
      }
      if (luminance_only && changed) texel[1] = texel[2] = texel[0];  // keep the R = G = B invariant of grey images
    }
  }
  return report;
}

}  // namespace blocklab
