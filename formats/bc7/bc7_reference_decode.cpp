// Spec-literal BC7 decoder following the KDFS "BPTC" chapter step by step (see bc7_reference_decode.h):
//   1. mode = index of the lowest set bit of the block (byte 0 == 0: reserved, all channels 0);
//   2. read partition, rotation and index-selection fields of the widths in the mode table;
//   3. read the endpoints: NS*2 values of R, then G, then B, then (if AB > 0) alpha;
//   4. read the P-bits (one per endpoint, or one per subset) and append each as the LSB of its endpoint's channels;
//   5. expand each endpoint to 8 bits by shifting it to the top and copying its top bits into the free low bits;
//   6. read the indices texel by texel; the anchor texel of each subset is read with one bit less;
//      for modes 4/5 a second index set follows, with texel 0 as its only anchor;
//   7. interpolate with the weight table of the index size: ((64 - w) * E0 + w * E1 + 32) >> 6;
//   8. swap alpha with the channel named by the rotation.
#include "formats/bc7/bc7_reference_decode.h"

#include "formats/bc7/bc7_tables.h"

namespace blocklab {
namespace bc7 {

namespace {

// A plain LSB-first reader over the 128 bits (bit k = bit k%8 of byte k/8), one bit at a time.
class PlainBitStream {
 public:
  explicit PlainBitStream(const std::uint8_t* bytes) : bytes_(bytes) {}
  int take(int count) {
    int value = 0;
    for (int i = 0; i < count; ++i) {
      const int bit = (bytes_[position_ / 8] >> (position_ % 8)) & 1;
      value |= bit << i;
      ++position_;
    }
    return value;
  }

 private:
  const std::uint8_t* bytes_;
  int position_ = 0;
};

int bit_replicated_to_8(int value, int bits) {
  // A value of `bits` bits moved to the top of a byte, its high bits repeated downwards into the empty low bits.
  int result = 0;
  int filled = 0;
  while (filled < 8) {
    const int shift = 8 - filled - bits;
    result |= shift >= 0 ? (value << shift) : (value >> -shift);
    filled += bits;
  }
  return result & 0xFF;
}

}  // namespace

void reference_decode(const std::uint8_t* bytes, std::uint8_t (&out)[16][4]) {
  PlainBitStream stream(bytes);
  int mode = 0;
  while (mode < 8 && stream.take(1) == 0) ++mode;
  if (mode == 8) {   // no mode bit in byte 0: reserved block
    for (auto& texel : out)
      for (auto& channel : texel) channel = 0;
    return;
  }
  const ModeInfo& m = mode_info(mode);
  const int partition = stream.take(m.partition_bits);
  const int rotation = stream.take(m.rotation_bits);
  const int index_selection = stream.take(m.index_selection_bits);

  const int endpoint_count = m.subset_count * 2;
  int endpoint[6][4] = {};   // [subset * 2 + endpoint][channel]
  int bits[4] = {m.color_bits, m.color_bits, m.color_bits, m.alpha_bits};
  for (int channel = 0; channel < 3; ++channel)
    for (int e = 0; e < endpoint_count; ++e) endpoint[e][channel] = stream.take(m.color_bits);
  if (m.alpha_bits > 0)
    for (int e = 0; e < endpoint_count; ++e) endpoint[e][3] = stream.take(m.alpha_bits);

  if (m.endpoint_pbits) {
    for (int e = 0; e < endpoint_count; ++e) {
      const int p = stream.take(1);
      for (int channel = 0; channel < 4; ++channel) endpoint[e][channel] = (endpoint[e][channel] << 1) | p;
    }
  }
  if (m.shared_pbits) {
    for (int subset = 0; subset < m.subset_count; ++subset) {
      const int p = stream.take(1);
      for (int e = subset * 2; e < subset * 2 + 2; ++e)
        for (int channel = 0; channel < 4; ++channel) endpoint[e][channel] = (endpoint[e][channel] << 1) | p;
    }
  }
  if (m.endpoint_pbits || m.shared_pbits)
    for (int channel = 0; channel < 4; ++channel)
      if (bits[channel] > 0) ++bits[channel];

  for (int e = 0; e < endpoint_count; ++e)
    for (int channel = 0; channel < 4; ++channel)
      endpoint[e][channel] = bits[channel] == 0 ? 255 : bit_replicated_to_8(endpoint[e][channel], bits[channel]);

  int subset_of[16];
  for (int texel = 0; texel < 16; ++texel) subset_of[texel] = subset_of_texel(m.subset_count, partition, texel);

  int index1[16] = {};
  for (int texel = 0; texel < 16; ++texel) {
    bool is_anchor = false;
    for (int subset = 0; subset < m.subset_count; ++subset)
      if (anchor_texel(m.subset_count, partition, subset) == texel) is_anchor = true;
    index1[texel] = stream.take(is_anchor ? m.index_bits - 1 : m.index_bits);
  }
  int index2[16] = {};
  if (m.index2_bits > 0)
    for (int texel = 0; texel < 16; ++texel) index2[texel] = stream.take(texel == 0 ? m.index2_bits - 1 : m.index2_bits);

  for (int texel = 0; texel < 16; ++texel) {
    const int s = subset_of[texel];
    int colour_index = index1[texel], colour_bits = m.index_bits;
    int alpha_index = index1[texel], alpha_bits = m.index_bits;
    if (m.index2_bits > 0) {
      alpha_index = index2[texel];
      alpha_bits = m.index2_bits;
      if (index_selection == 1) {
        colour_index = index2[texel];
        colour_bits = m.index2_bits;
        alpha_index = index1[texel];
        alpha_bits = m.index_bits;
      }
    }
    const int colour_weight = index_weights(colour_bits)[colour_index];
    const int alpha_weight = index_weights(alpha_bits)[alpha_index];
    int rgba[4];
    for (int channel = 0; channel < 4; ++channel) {
      const int weight = channel == 3 ? alpha_weight : colour_weight;
      rgba[channel] = ((64 - weight) * endpoint[s * 2][channel] + weight * endpoint[s * 2 + 1][channel] + 32) >> 6;
    }
    if (rotation == 1) { const int t = rgba[0]; rgba[0] = rgba[3]; rgba[3] = t; }
    if (rotation == 2) { const int t = rgba[1]; rgba[1] = rgba[3]; rgba[3] = t; }
    if (rotation == 3) { const int t = rgba[2]; rgba[2] = rgba[3]; rgba[3] = t; }
    for (int channel = 0; channel < 4; ++channel) out[texel][channel] = static_cast<std::uint8_t>(rgba[channel]);
  }
}

}  // namespace bc7
}  // namespace blocklab
