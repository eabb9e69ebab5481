// Golden bytes of the `compete` format (formats/compete/README.md): the bundled HDR samples encoded with the default
// `medium` preset and with `fast`, FNV-1a 64 hashes of the packed blocks and of the decoded floats compared with
// committed constants. Any change of the encoder's answers (the munkberg and bc6h block encoders it calls included)
// or of a decoder shows here; a deliberate change must bump the format's revision() (and decoder_revision() when only
// the encoder changed, formats/format.h). To regenerate after a deliberate change: run this test; each failing
// EXPECT_EQ prints the actual value.
#include <gtest/gtest.h>

#include "golden_hash.h"

#include <map>
#include <string>

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
  std::uint64_t blocks_hash, decoded_hash;
};

const Golden kGolden[] = {
    {"hdr/Desk.exr", {}, 10259213869701361311ull, 14697875104432094299ull},
    {"hdr/blender_world_sunset.exr", {}, 11585130332998527173ull, 10513537238614904253ull},
    {"hdr/Desk.exr", {{"preset", "fast"}}, 1140558483701683855ull, 14833031665721635804ull},
};

TEST(CompeteGolden, EncodedBytesAndDecodedFloatsOfTheSamplesMatchTheCommittedHashes) {
  const Format& format = find_format("compete");
  for (const Golden& golden : kGolden) {
    const std::string path = std::string(BLOCKLAB_TEST_SAMPLES) + "/" + golden.image;
    Image image = read_image(path);
    apply_input_policy(image, InputPolicy::clamp, path);
    const EncodedTexture texture =
        format.encode(image, resolve_format_options(format, golden.options), CodecContext{2, 1});
    const Image decoded = format.decode(texture, CodecContext{2, 1});
    std::string label = golden.image;
    for (const auto& option : golden.options) label += " " + option.first + "=" + option.second;
    EXPECT_EQ(fnv1a64(texture.blocks.data(), texture.blocks.size()), golden.blocks_hash) << label;
    EXPECT_EQ(hash_floats(decoded.pixels), golden.decoded_hash) << label;
  }
}

}  // namespace
}  // namespace blocklab
