// Golden bytes of the `compete` format (formats/compete/README.md): the bundled HDR samples encoded with the default
// `medium` preset and with `fast`, FNV-1a 64 hashes of the packed blocks and of the decoded floats compared with
// committed constants. Any change of the encoder's answers (the munkberg and bc6h block encoders it calls included)
// or of a decoder shows here; a deliberate change must bump the format's revision() (and decoder_revision() when only
// the encoder changed, formats/format.h). To regenerate after a deliberate change: run this test; each failing
// EXPECT_EQ prints the actual value.
#include <gtest/gtest.h>

#include "golden_sample_encoding.h"

#include <map>
#include <string>

namespace blocklab {
namespace {

struct Golden {
  const char* image;
  std::map<std::string, std::string> options;
  std::uint64_t blocks_hash, decoded_hash;
};

const Golden kGolden[] = {
    {"hdr/Desk.exr", {}, 10541287926909093353ull, 11410192684743961542ull},
    {"hdr/blender_world_sunset.exr", {}, 15125471775916130176ull, 14942115197760231436ull},
    {"hdr/Desk.exr", {{"preset", "fast"}}, 16772701179325719068ull, 13772084176898816106ull},
};

TEST(CompeteGolden, EncodedBytesAndDecodedFloatsOfTheSamplesMatchTheCommittedHashes) {
  for (const Golden& golden : kGolden) {
    const golden::SampleHashes hashes = golden::hash_sample_encoding("compete", golden.image, golden.options);
    std::string label = golden.image;
    for (const auto& option : golden.options) label += " " + option.first + "=" + option.second;
    EXPECT_EQ(hashes.blocks, golden.blocks_hash) << label;
    EXPECT_EQ(hashes.decoded, golden.decoded_hash) << label;
  }
}

}  // namespace
}  // namespace blocklab
