// The `compete` reference decoder (compete_reference_decode.h): README.md's "Block" table read literally.
#include "formats/compete/compete_reference_decode.h"

#include "formats/bc6h/bc6h_half.h"
#include "formats/bc6h/bc6h_reference_decode.h"

namespace blocklab::compete {

namespace {

int read_bit(const std::uint8_t* bytes, int k) { return (bytes[k / 8] >> (k % 8)) & 1; }

// README "Block": per Munkberg mode (selector read from the Munkberg block's first bits) the two bits not stored,
// each with the bit it copies (-1: always 0).
struct NotStored {
  int position;
  int copy_of;
};
const NotStored kShapeII[2] = {{25, 31}, {51, -1}};     // v1 LSB <- v1 MSB; texel 0 luminance index MSB = 0
const NotStored kShapeI[2] = {{33, 40}, {41, 48}};      // Y0 LSB <- Y0 MSB; Y1 LSB <- Y1 MSB
const NotStored kExtS3tc[2] = {{19, 25}, {42, 48}};     // endpoint 0 / 1 third channel LSB <- its MSB
const NotStored kTwoPlane[2] = {{4, 12}, {27, 35}};     // plane 0 / 1 offset LSB <- its MSB
const NotStored kDct[2] = {{4, 12}, {66, 72}};          // Ybar DC LSB <- its MSB; u DC LSB <- its MSB

}  // namespace

BlockTexels reference_decode_block(const std::uint8_t* bytes, const munkberg::ModeContext& context) {
  if (!(read_bit(bytes, 0) == 1 && read_bit(bytes, 1) == 1)) {
    // A BC6H UF16 block as it stands.
    std::uint16_t halves[16][3];
    bc6h::reference_decode(bytes, false, halves);
    BlockTexels block;
    for (int i = 0; i < 16; ++i) {
      for (int c = 0; c < 3; ++c) block.rgba[i][c] = bc6h::half_bits_to_float(halves[i][c]);
      block.rgba[i][3] = 1.0f;
    }
    return block;
  }
  // Munkberg selector: 0 shape II; 1,0 shape I; 1,1,0 ext S3TC; 1,1,1,0 two-plane; 1,1,1,1 DCT (compete bits 2..5).
  const NotStored* not_stored = kShapeII;
  if (read_bit(bytes, 2) == 1) {
    if (read_bit(bytes, 3) == 0)
      not_stored = kShapeI;
    else if (read_bit(bytes, 4) == 0)
      not_stored = kExtS3tc;
    else
      not_stored = read_bit(bytes, 5) == 0 ? kTwoPlane : kDct;
  }
  int munkberg_bits[128] = {};
  int next = 2;   // the next stored compete bit
  for (int j = 0; j < 128; ++j) {
    if (j == not_stored[0].position || j == not_stored[1].position) continue;
    munkberg_bits[j] = read_bit(bytes, next++);
  }
  for (int d = 0; d < 2; ++d)
    munkberg_bits[not_stored[d].position] = not_stored[d].copy_of < 0 ? 0 : munkberg_bits[not_stored[d].copy_of];
  std::uint8_t munkberg_block[16] = {};
  for (int j = 0; j < 128; ++j) munkberg_block[j / 8] |= static_cast<std::uint8_t>(munkberg_bits[j] << (j % 8));
  return munkberg::reference_decode_any_block(munkberg_block, context);
}

}  // namespace blocklab::compete
