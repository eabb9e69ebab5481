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
    {"bc6h", "hdr/Desk.exr", "fast", 4605032732112527657ull, 1509446682516253311ull},
    {"bc6h", "hdr/Desk.exr", "medium", 5037376385118782860ull, 15537679291071037672ull},
    {"bc6h", "hdr/Desk.exr", "thorough", 17449679609067885310ull, 14321529311801352725ull},
    {"bc6h", "hdr/hdr-rgb-arboretum.hdr", "medium", 718423709807803459ull, 18378887909814203800ull},
    {"bc6h", "hdr/blender_world_sunset.exr", "medium", 7596479602003906725ull, 2085348841150698835ull},
    {"bc6h_sf", "hdr/Desk.exr", "medium", 10913506441747310572ull, 5899966113318598682ull},
    {"bc6h_sf", "hdr/hdr-rgb-arboretum.hdr", "medium", 1522450924166819324ull, 6415713997552269084ull},
    {"bc6h_sf", "hdr/blender_world_sunset.exr", "medium", 12017239185282807892ull, 16643469969099102189ull},
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
