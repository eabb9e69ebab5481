// The IEEE bit pattern of a float, for tests that compare decoders bit for bit (ASSERT_EQ on the patterns prints
// both values and tells -0 from 0, which EXPECT_EQ on floats would not).
#pragma once

#include <cstdint>
#include <cstring>

namespace blocklab {

inline std::uint32_t float_bits(float value) {
  std::uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

}  // namespace blocklab
