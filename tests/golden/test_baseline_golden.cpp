// Golden bytes of the two bit-exact baselines (fp16, rgbe): a small synthetic HDR image built from exact integer
// arithmetic and ldexp (no transcendental functions, so it is the same on every machine) is encoded with each
// format, and the FNV-1a 64-bit hashes of the packed blocks and of the decoded floats are compared with constants
// committed here. A change of these bytes must be deliberate: it also needs Format::revision() bumped (cached
// results keyed on the old bytes become stale).
//
// The committed hashes were cross-checked when written against an independent computation (numpy's float16
// conversion for fp16; a Python transcription of Ward's float2rgbe / rgbe2float for rgbe, with the same
// clamp-to-edge tiling): all five agreed.
//
// To regenerate after a deliberate change: build and run this test (Release, BLOCKLAB_INVARIANT=ON); each failing
// EXPECT_EQ prints the actual hash in decimal ("Which is: ..."); paste it into kGolden below (with the ull suffix)
// and bump the format's revision() in the same change.
#include <gtest/gtest.h>

#include "golden_hash.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "formats/registry.h"

namespace blocklab {
namespace {

using golden::fnv1a64;
using golden::hash_floats;

// 19x11 (not a multiple of 4: exercises edge padding), values over 2^-20 .. 2^20 from integer formulas, with
// exact zeros, a value above the half range (fp16 clamps it) and values below Ward's 1e-32 threshold.
Image synthetic_hdr_image() {
  Image image(19, 11);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const int mantissa = (x * 37 + y * 101 + c * 53) % 997 + 1;   // 1 .. 997
        const int exponent = (x + 2 * y + 3 * c) % 40 - 20;           // -20 .. 19
        float value = std::ldexp(static_cast<float>(mantissa) / 1024.0f, exponent);
        if ((x + y) % 7 == 0) value = 0.0f;
        image.texel(x, y)[c] = value;
      }
  image.texel(3, 4)[0] = 100000.0f;                 // above 65504
  image.texel(5, 5)[1] = std::ldexp(1.0f, -110);    // below 1e-32 (RGBE zero when it is the max channel)
  image.texel(6, 5)[0] = image.texel(6, 5)[1] = image.texel(6, 5)[2] = std::ldexp(1.0f, -110);
  return image;
}

struct Golden {
  const char* format;
  FormatOptions options;
  std::uint64_t blocks_hash;
  std::uint64_t decoded_hash;
};

const std::vector<Golden> kGolden = {
    {"fp16", {}, 8118211292215516192ull, 4230540343443237673ull},
    {"rgbe", {{"decode_offset", "none"}}, 13859490571176310606ull, 8924631942872289615ull},
    {"rgbe", {{"decode_offset", "half"}}, 13859490571176310606ull, 9260801495201113777ull},
};

TEST(BaselineGolden, EncodedBytesAndDecodedFloatsMatchTheCommittedHashes) {
  const Image image = synthetic_hdr_image();
  for (const Golden& golden : kGolden) {
    SCOPED_TRACE(std::string(golden.format) + " " + (golden.options.empty() ? "" : golden.options.begin()->second));
    const Format& format = find_format(golden.format);
    const FormatOptions options = resolve_format_options(format, golden.options);
    const EncodedTexture texture = format.encode(image, options, CodecContext{2, 1});
    EXPECT_EQ(texture.blocks.size(), 15u * static_cast<std::size_t>(format.block_bytes(options)));   // 5 x 3 blocks
    const Image decoded = format.decode(texture, CodecContext{2, 1});
    EXPECT_EQ(fnv1a64(texture.blocks.data(), texture.blocks.size()), golden.blocks_hash);
    EXPECT_EQ(hash_floats(decoded.pixels), golden.decoded_hash);
  }
}

TEST(BaselineGolden, HashFunctionMatchesPublishedFnv1aVectors) {
  // Reference values of FNV-1a 64 (IETF draft-eastlake-fnv, test vectors for "" and "a").
  EXPECT_EQ(fnv1a64(nullptr, 0), 0xcbf29ce484222325ull);
  const std::uint8_t a = 'a';
  EXPECT_EQ(fnv1a64(&a, 1), 0xaf63dc4c8601ec8cull);
}

}  // namespace
}  // namespace blocklab
