// Golden bytes of the `munkberg` format (formats/munkberg/README.md): the bundled HDR samples encoded with the
// `thorough` preset restricted to the paper's format (modes=both: shape II + shape I, the default options of revisions 3
// and 4; revision 4 = revision 3's bytes, checked against the revision 3 binary when these were recorded), with every
// mode competing in the full competition (mode_predictor 0: adds extended S3TC, two-plane and the fixed-rate DCT with
// the committed tables; revision 4's bytes), revision 4's `medium` (modes=both), and the defaults of revision 5
// (`thorough` and `medium` with all modes and the mode predictor), FNV-1a 64 hashes of the
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
    {"hdr/Desk.exr", {{"preset", "thorough"}, {"modes", "both"}}, 11793414465926949265ull, 9427074733560139116ull},
    {"hdr/blender_world_sunset.exr", {{"preset", "thorough"}, {"modes", "both"}}, 9922741913128008020ull,
     10228367441297611543ull},
    {"hdr/Desk.exr", {{"preset", "thorough"}, {"modes", "all"}, {"mode_predictor", "0"}}, 16207498588969861721ull,
     10308150686124917531ull},
    {"hdr/Desk.exr", {{"preset", "thorough"}}, 14766546080880841456ull, 16989714075717658000ull},
    {"hdr/Desk.exr", {{"modes", "both"}, {"mode_predictor", "0"}}, 12831275311216237000ull, 8457622856682159619ull},
    {"hdr/Desk.exr", {}, 8058159392523760478ull, 5090784914128485255ull},
    {"hdr/blender_world_sunset.exr", {}, 16662038727433958018ull, 4272461668240671310ull},
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
