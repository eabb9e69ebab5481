// Golden bytes of the `wang` format (formats/wang/README.md): a 64x48 crop of each bundled HDR sample encoded with
// the default options (LUVW, residual S, two zones, 1D codec, preset medium, eq. 2 linear t1 search) and Desk with
// the plain BC3 codec, FNV-1a 64 hashes of the packed blocks, of the decoded floats and of the side data compared
// with committed constants. A deliberate change of the encoder's answers or of the decoder must bump
// WangFormat::revision() (the experiment cache key; decoder_revision() too when the decoding changes). The encoder
// uses sqrt only (no transcendental functions); the Debian 12 toolchain of CI is the reference. To regenerate after
// a deliberate change: run this test; each failing EXPECT_EQ prints the actual value.
#include <gtest/gtest.h>

#include "golden_hash.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "core/image_io.h"
#include "core/input_policy.h"
#include "formats/registry.h"

namespace blocklab {
namespace {

using golden::fnv1a64;
using golden::hash_floats;

struct Golden {
  const char* image;
  std::map<std::string, std::string> options;
  std::uint64_t blocks_hash, decoded_hash, side_data_hash;
};

const Golden kGolden[] = {
    {"hdr/Desk.exr", {}, 14504147107721668736ull, 6963038869240888079ull, 16466038821626550341ull},
    {"hdr/hdr-rgb-arboretum.hdr", {}, 6611928073175526308ull, 16293604668714975285ull, 16309324375843275829ull},
    {"hdr/blender_world_sunset.exr", {}, 4455844876473064064ull, 3991944308515913938ull, 2727416857512798951ull},
    {"hdr/Desk.exr", {{"codec", "bc3"}}, 12294016117713809113ull, 4088048060516073506ull, 14628979858438444124ull},
};

std::uint64_t hash_side_data(const EncodedTexture& texture) {
  std::vector<std::uint8_t> bytes;
  for (const auto& entry : texture.side_data) {
    bytes.insert(bytes.end(), entry.first.begin(), entry.first.end());
    bytes.push_back(0);
    for (double value : entry.second) {
      std::uint64_t bits;
      std::memcpy(&bits, &value, sizeof bits);
      for (int shift = 0; shift < 64; shift += 8) bytes.push_back(static_cast<std::uint8_t>(bits >> shift));
    }
  }
  return fnv1a64(bytes.data(), bytes.size());
}

TEST(WangGolden, EncodedBytesDecodedFloatsAndSideDataOfSampleCropsMatchTheCommittedHashes) {
  const Format& format = find_format("wang");
  for (const Golden& golden : kGolden) {
    const std::string path = std::string(BLOCKLAB_TEST_SAMPLES) + "/" + golden.image;
    Image image = read_image(path);
    apply_input_policy(image, InputPolicy::clamp, path);
    image = crop_image(image, 0, 0, std::min(image.width, 64), std::min(image.height, 48));
    const EncodedTexture texture =
        format.encode(image, resolve_format_options(format, golden.options), CodecContext{2, 1});
    const Image decoded = format.decode(texture, CodecContext{2, 1});
    const std::string label = std::string(golden.image) + (golden.options.empty() ? " default" : " codec=bc3");
    EXPECT_EQ(fnv1a64(texture.blocks.data(), texture.blocks.size()), golden.blocks_hash) << label;
    EXPECT_EQ(hash_floats(decoded.pixels), golden.decoded_hash) << label;
    EXPECT_EQ(hash_side_data(texture), golden.side_data_hash) << label;
  }
}

}  // namespace
}  // namespace blocklab
