// Golden bytes of the `downscaled` format (formats/downscaled/README.md): a 64x48 crop of the bundled kodim03 at the
// three scales of Mavridis & Papaioannou 2012's Table 4 baseline (DXT1 at 71 %, 75 %, 86 %) and the gray one (BC4 of
// BT.601 luma at bpp = 2), preset medium otherwise; FNV-1a 64 hashes of the stored blocks and of the decoded floats
// compared with committed constants, and the reduced size. A deliberate change of the resampling, of the inner encoder
// or of the decoder must bump DownscaledFormat::revision() (or the inner format's). The Lanczos weights use sin; the
// Debian 12 toolchain of CI is the reference. To regenerate after a deliberate change: run this test; each failing
// EXPECT_EQ prints the actual value.
#include <gtest/gtest.h>

#include "golden_hash.h"

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
  std::map<std::string, std::string> options;
  std::vector<double> reduced_size;
  std::uint64_t blocks_hash, decoded_hash;
};

TEST(DownscaledGolden, StoredBlocksAndDecodedFloatsOfTheKodimCropMatchTheCommittedHashes) {
  const Golden kGolden[] = {
      {{{"scale", "0.71"}}, {45, 34}, 3810128197710665501ull, 5354802870596293069ull},
      {{{"scale", "0.75"}}, {48, 36}, 9471096822409767512ull, 13484765128047966685ull},
      {{{"scale", "0.86"}}, {55, 41}, 6850607709458130718ull, 3411066321198013203ull},
      {{{"inner", "bc4"}, {"bpp", "2"}, {"source", "bt601_luma"}},
       {45, 34},
       11881090374020046833ull,
       12107466460436618700ull},
  };
  const Format& format = find_format("downscaled");
  const std::string path = std::string(BLOCKLAB_TEST_SAMPLES) + "/ldr/kodak/kodim03.png";
  Image image = read_image(path);
  apply_input_policy(image, InputPolicy::clamp, path);
  image = crop_image(image, 0, 0, 64, 48);
  for (const Golden& golden : kGolden) {
    const std::string label = golden.options.begin()->second;
    const EncodedTexture texture =
        format.encode(image, resolve_format_options(format, FormatOptions(golden.options.begin(), golden.options.end())),
                      CodecContext{2, 1});
    const Image decoded = format.decode(texture, CodecContext{2, 1});
    EXPECT_EQ(texture.side_data.at("reduced_size"), golden.reduced_size) << label;
    EXPECT_EQ(fnv1a64(texture.blocks.data(), texture.blocks.size()), golden.blocks_hash) << label;
    EXPECT_EQ(hash_floats(decoded.pixels), golden.decoded_hash) << label;
  }
}

}  // namespace
}  // namespace blocklab
