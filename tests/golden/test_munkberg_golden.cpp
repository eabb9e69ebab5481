// Golden bytes of the `munkberg` format (formats/munkberg/README.md): the bundled HDR samples encoded with the
// `thorough` preset (the full global search, the default options of revisions 3 and 4: the paper's format, shape II +
// shape I; revision 4 = revision 3's bytes, checked against the revision 3 binary when these were recorded), with the
// default `medium` preset, and with every mode
// competing (adds extended S3TC, two-plane and the fixed-rate DCT with the committed tables), FNV-1a 64 hashes of the
// packed blocks and of the decoded floats compared with committed constants. Any change of the encoder's answers
// (the solver library's procrustes included, which the shape modes call) or of a decoder shows here; a deliberate
// change must bump MunkbergFormat::revision() (the experiment cache key); if only the encoder changed, also override
// decoder_revision() with the old number, so .blk files written before stay readable (formats/format.h). The encoder uses log2/exp2/pow of glibc; the Debian 12 toolchain of
// CI is the reference. To regenerate after a deliberate change: run this test; each failing EXPECT_EQ prints the
// actual value.
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
    {"hdr/Desk.exr", {{"preset", "thorough"}}, 11793414465926949265ull, 9427074733560139116ull},
    {"hdr/blender_world_sunset.exr", {{"preset", "thorough"}}, 9922741913128008020ull, 10228367441297611543ull},
    {"hdr/Desk.exr", {{"preset", "thorough"}, {"modes", "all"}}, 16207498588969861721ull, 10308150686124917531ull},
    {"hdr/Desk.exr", {}, 12831275311216237000ull, 8457622856682159619ull},
    {"hdr/blender_world_sunset.exr", {}, 4746536326669360416ull, 4092404927133485215ull},
};

TEST(MunkbergGolden, EncodedBytesAndDecodedFloatsOfTheSamplesMatchTheCommittedHashes) {
  const Format& format = find_format("munkberg");
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
