// IEEE 754 binary16 ("half") conversions for BC6H: the decoder's output bits to float (exact) and the encoder's
// input float to half bits (round to nearest, ties to even, Imath::half; magnitudes above 65504 clamp to 65504 so
// no infinity is ever encoded, as the KDFS BC6H note asks of encoders).
#pragma once

#include <cstdint>

namespace blocklab {
namespace bc6h {

float half_bits_to_float(std::uint16_t bits);
std::uint16_t float_to_half_bits(float value);

}  // namespace bc6h
}  // namespace blocklab
