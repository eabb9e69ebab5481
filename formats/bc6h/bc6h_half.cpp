// Half-float conversions of bc6h_half.h through Imath::half (Imath 3.1 half.h).
#include "formats/bc6h/bc6h_half.h"

#include <Imath/half.h>

namespace blocklab {
namespace bc6h {

float half_bits_to_float(std::uint16_t bits) {
  Imath::half value;
  value.setBits(bits);
  return static_cast<float>(value);
}

std::uint16_t float_to_half_bits(float value) {
  constexpr float kLargestFiniteHalf = 65504.0f;
  if (value > kLargestFiniteHalf) value = kLargestFiniteHalf;
  if (value < -kLargestFiniteHalf) value = -kLargestFiniteHalf;
  return Imath::half(value).bits();
}

}  // namespace bc6h
}  // namespace blocklab
