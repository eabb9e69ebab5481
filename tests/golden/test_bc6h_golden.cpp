// Golden bytes of the `bc6h` and `bc6h_sf` formats (formats/bc6h/README.md): a 64x48 crop of each bundled HDR sample
// encoded at every preset (bc6h) and at the default preset (bc6h_sf); FNV-1a 64 hashes of the packed blocks and of
// the decoded floats compared with committed constants. A deliberate change of the encoder's answers or of the decoder
// must bump the format's revision() (decoder_revision() too when the decoding changes). The encoder uses sqrt and
// ldexp only; the Debian 12 toolchain of CI is the reference. To regenerate after a deliberate change: run this test;
// each failing EXPECT_EQ prints the actual value.
#include <gtest/gtest.h>

#include "golden_hash.h"

#include <algorithm>
#include <string>

#include "core/image_io.h"
#include "core/input_policy.h"
#include "formats/registry.h"

namespace blocklab {
namespace {

using golden::fnv1a64;
using golden::hash_floats;

struct Golden {
  const char* format;
  const char* image;
  const char* preset;
  std::uint64_t blocks_hash, decoded_hash;
};

const Golden kGolden[] = {
    {"bc6h", "hdr/Desk.exr", "fast", 2567576652277665160ull, 10739641479585897526ull},
    {"bc6h", "hdr/Desk.exr", "medium", 16000796426280969867ull, 8145183659549671411ull},
    {"bc6h", "hdr/Desk.exr", "thorough", 14843769600282142782ull, 9838902769009638120ull},
    {"bc6h", "hdr/hdr-rgb-arboretum.hdr", "medium", 5705138958912860919ull, 867358773946011855ull},
    {"bc6h", "hdr/blender_world_sunset.exr", "medium", 14689267483388773591ull, 2610364306397750207ull},
    {"bc6h_sf", "hdr/Desk.exr", "medium", 17936034212574651595ull, 10400394742457537430ull},
    {"bc6h_sf", "hdr/hdr-rgb-arboretum.hdr", "medium", 769770394610964321ull, 6565731137544836550ull},
    {"bc6h_sf", "hdr/blender_world_sunset.exr", "medium", 15618809358056426007ull, 14368479827426110021ull},
};

TEST(Bc6hGolden, EncodedBytesAndDecodedFloatsOfSampleCropsMatchTheCommittedHashes) {
  for (const Golden& golden : kGolden) {
    const Format& format = find_format(golden.format);
    const std::string path = std::string(BLOCKLAB_TEST_SAMPLES) + "/" + golden.image;
    Image image = read_image(path);
    apply_input_policy(image, InputPolicy::clamp, path);
    image = crop_image(image, 0, 0, std::min(image.width, 64), std::min(image.height, 48));
    const EncodedTexture texture =
        format.encode(image, resolve_format_options(format, {{"preset", golden.preset}}), CodecContext{2, 1});
    const Image decoded = format.decode(texture, CodecContext{2, 1});
    const std::string label = std::string(golden.format) + " " + golden.image + " " + golden.preset;
    EXPECT_EQ(fnv1a64(texture.blocks.data(), texture.blocks.size()), golden.blocks_hash) << label;
    EXPECT_EQ(hash_floats(decoded.pixels), golden.decoded_hash) << label;
  }
}

}  // namespace
}  // namespace blocklab
