// Golden bytes of the `mavridis` format (formats/mavridis/README.md): a 64x48 crop of the bundled kodim03 encoded
// at each Table 2 rate with the default options otherwise (PI-Haar w = 0.4, YCoCg-R, preset medium), FNV-1a 64
// hashes of the packed blocks, of the decoded floats and of the side data compared with committed constants. A
// deliberate change of the encoder's answers or of the decoder must bump MavridisFormat::revision(). The encoder
// uses pow (the gamma of section 3.2); the Debian 12 toolchain of CI is the reference. To regenerate after a
// deliberate change: run this test; each failing EXPECT_EQ prints the actual value.
#include <gtest/gtest.h>

#include "golden_hash.h"

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
  const char* bpp;
  std::uint64_t blocks_hash, decoded_hash, side_data_hash;
};

const Golden kGolden[] = {
    {"5", 2726090969817431937ull, 10235045954574315636ull, 1212121325714962592ull},
    {"3", 13652321586691667472ull, 4758625322593005244ull, 12337899825990281499ull},
    {"2.25", 8726412278722384845ull, 5513622821325783226ull, 16539037762103027095ull},
    {"2", 16977656565758334575ull, 5907919499159121266ull, 3052820934804172804ull},
};

// Keys and values of the side data, the values as their little-endian IEEE bytes (the machines CI runs on).
std::uint64_t hash_side_data(const EncodedTexture& texture) {
  std::string text;
  for (const auto& [key, values] : texture.side_data) {
    text += key + '=';
    text.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(double));
  }
  return fnv1a64(reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
}

TEST(MavridisGolden, EncodedBytesDecodedFloatsAndSideDataOfTheKodimCropMatchTheCommittedHashes) {
  const Format& format = find_format("mavridis");
  const std::string path = std::string(BLOCKLAB_TEST_SAMPLES) + "/ldr/kodak/kodim03.png";
  Image image = read_image(path);
  apply_input_policy(image, InputPolicy::clamp, path);
  image = crop_image(image, 0, 0, 64, 48);
  for (const Golden& golden : kGolden) {
    const EncodedTexture texture = format.encode(image, resolve_format_options(format, {{"bpp", golden.bpp}}),
                                                 CodecContext{2, 1});
    const Image decoded = format.decode(texture, CodecContext{2, 1});
    EXPECT_EQ(fnv1a64(texture.blocks.data(), texture.blocks.size()), golden.blocks_hash) << "bpp " << golden.bpp;
    EXPECT_EQ(hash_floats(decoded.pixels), golden.decoded_hash) << "bpp " << golden.bpp;
    EXPECT_EQ(hash_side_data(texture), golden.side_data_hash) << "bpp " << golden.bpp;
  }
}

}  // namespace
}  // namespace blocklab
