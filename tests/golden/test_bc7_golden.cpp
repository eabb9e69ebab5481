// Golden bytes of the `bc7` encoder (formats/bc7/README.md): a 64x48 crop of the bundled kodim03 encoded with each
// preset (fast, medium, thorough) and with the channel weights 0.6,0.2,0.2 that the mavridis format passes; FNV-1a 64
// hashes of the packed blocks and of the decoded floats compared with committed constants. The encoder is integer
// and float arithmetic without transcendental functions under the invariant build flags, so the bytes are the same
// on every machine. A deliberate change of the encoder's answers must bump Bc7Format::revision() (the decoder's
// answers: decoder_revision() too). To regenerate after a deliberate change: run this test; each failing EXPECT_EQ
// prints the actual value.
#include <gtest/gtest.h>

#include "golden_hash.h"

#include <string>

#include "core/image_io.h"
#include "core/input_policy.h"
#include "formats/registry.h"

namespace blocklab {
namespace {

using golden::fnv1a64;
using golden::hash_floats;

struct Golden {
  const char* preset;
  const char* weights;
  std::uint64_t blocks_hash, decoded_hash;
};

const Golden kGolden[] = {
    {"fast", "1,1,1,1", 4749092816266161230ull, 9147975880839769592ull},
    {"medium", "1,1,1,1", 13555985088786735ull, 6308502277198244113ull},
    {"thorough", "1,1,1,1", 17531478248862247136ull, 17641077808341626873ull},
    {"medium", "0.6,0.2,0.2,1", 3868537531517339453ull, 10009875345897898165ull},
};

TEST(Bc7Golden, EncodedBytesAndDecodedFloatsOfTheKodimCropMatchTheCommittedHashes) {
  const Format& format = find_format("bc7");
  const std::string path = std::string(BLOCKLAB_TEST_SAMPLES) + "/ldr/kodak/kodim03.png";
  Image image = read_image(path);
  apply_input_policy(image, InputPolicy::clamp, path);
  image = crop_image(image, 0, 0, 64, 48);
  for (const Golden& golden : kGolden) {
    const EncodedTexture texture = format.encode(
        image, resolve_format_options(format, {{"preset", golden.preset}, {"weights", golden.weights}}),
        CodecContext{2, 1});
    const Image decoded = format.decode(texture, CodecContext{2, 1});
    EXPECT_EQ(fnv1a64(texture.blocks.data(), texture.blocks.size()), golden.blocks_hash)
        << golden.preset << " weights " << golden.weights;
    EXPECT_EQ(hash_floats(decoded.pixels), golden.decoded_hash) << golden.preset << " weights " << golden.weights;
  }
}

}  // namespace
}  // namespace blocklab
