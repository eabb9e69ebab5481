// S3TC robustness: random bytes of every block size decode without crashing to finite values in [0, 1]
// through the bc1/bc3/bc4 Formats and oracles; the encoders survive extreme inputs (HDR values above 1, zeros,
// odd sizes); seeded random mutations of real DDS files give either blocklab::Error or a texture that decodes --
// never a crash or another exception type. Run under BLOCKLAB_SANITIZE=ON to also catch memory errors.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/error.h"
#include "formats/bc1/bc1_block.h"
#include "formats/bc3/bc3_block.h"
#include "formats/bc4/bc4_block.h"
#include "formats/common/dds.h"
#include "formats/registry.h"

namespace blocklab {
namespace {

void expect_unit_range(const Image& image, const std::string& context) {
  for (float value : image.pixels) {
    ASSERT_TRUE(std::isfinite(value)) << context;
    ASSERT_GE(value, 0.0f) << context;
    ASSERT_LE(value, 1.0f) << context;
  }
}

TEST(S3tcFuzz, RandomBlocksOfRandomSizesDecodeToTheUnitRange) {
  std::mt19937_64 random(51);
  for (const char* name : {"bc1", "bc3", "bc4"}) {
    const Format& format = find_format(name);
    for (int trial = 0; trial < 60; ++trial) {
      EncodedTexture texture;
      texture.format = name;
      texture.options = resolve_format_options(format, {});
      texture.width = 1 + static_cast<int>(random() % 70);
      texture.height = 1 + static_cast<int>(random() % 70);
      texture.channels = (trial % 3 == 0) ? 4 : 3;
      texture.block_bytes = format.block_bytes(texture.options);
      const BlockGrid grid(texture.width, texture.height);
      texture.blocks.resize(grid.block_count() * static_cast<std::size_t>(texture.block_bytes));
      for (auto& byte : texture.blocks) byte = static_cast<std::uint8_t>(random());
      expect_unit_range(format.decode(texture, CodecContext{0, 1}), name);
    }
  }
  // The oracles on their own, a million blocks in total.
  for (int i = 0; i < 300000; ++i) {
    std::uint8_t block[16];
    for (auto& byte : block) byte = static_cast<std::uint8_t>(random());
    const BlockTexels bc1 = reference_decode_bc1_block(block), bc3 = reference_decode_bc3_block(block);
    const std::array<float, 16> bc4 = reference_decode_bc4_block(block);
    for (int t = 0; t < 16; ++t) {
      ASSERT_TRUE(bc4[t] >= 0.0f && bc4[t] <= 1.0f);
      for (int c = 0; c < 4; ++c) ASSERT_TRUE(bc1.rgba[t][c] >= 0.0f && bc3.rgba[t][c] <= 1.0f);
    }
  }
}

TEST(S3tcFuzz, EncodersSurviveExtremeAndDegenerateInputs) {
  std::mt19937_64 random(52);
  for (const char* name : {"bc1", "bc3", "bc4"}) {
    const Format& format = find_format(name);
    for (const std::string search : {"fast", "default", "exhaustive"}) {
      for (int trial = 0; trial < 6; ++trial) {
        Image image(1 + static_cast<int>(random() % 13), 1 + static_cast<int>(random() % 13), trial % 2 ? 4 : 3);
        for (float& value : image.pixels) {
          const int kind = static_cast<int>(random() % 4);
          // zeros, HDR values far above 1, tiny values, ordinary code values
          value = kind == 0 ? 0.0f : kind == 1 ? 1000.0f : kind == 2 ? 1e-30f : (random() % 256) / 255.0f;
        }
        const EncodedTexture texture =
            format.encode(image, resolve_format_options(format, {{"search", search}}), CodecContext{0, 1});
        expect_unit_range(format.decode(texture, CodecContext{0, 1}), std::string(name) + " " + search);
      }
    }
  }
}

TEST(S3tcFuzz, MutatedDdsFilesGiveErrorsOrDecodableTextures) {
  std::mt19937_64 random(53);
  for (const char* name : {"bc1", "bc3", "bc4"}) {
    const Format& format = find_format(name);
    Image image(10, 9, 4);
    for (float& value : image.pixels) value = (random() % 256) / 255.0f;
    const std::vector<std::uint8_t> good =
        dds_bytes(format.encode(image, resolve_format_options(format, {}), CodecContext{1, 1}), "memory");
    for (int trial = 0; trial < 4000; ++trial) {
      std::vector<std::uint8_t> bytes = good;
      const int edits = 1 + static_cast<int>(random() % 4);
      for (int e = 0; e < edits; ++e) {
        const int kind = static_cast<int>(random() % 3);
        const std::size_t at = random() % (bytes.size() + 1);
        // Mutations concentrate on the 148 header bytes half of the time.
        const std::size_t position = (random() & 1) ? at % 148 : at;
        if (kind == 0 && position < bytes.size()) bytes[position] = static_cast<std::uint8_t>(random());
        else if (kind == 1) bytes.insert(bytes.begin() + static_cast<std::ptrdiff_t>(std::min(position, bytes.size())), static_cast<std::uint8_t>(random()));
        else if (!bytes.empty() && position < bytes.size()) bytes.erase(bytes.begin() + static_cast<std::ptrdiff_t>(position));
      }
      try {
        const EncodedTexture texture = parse_dds(bytes, "fuzz.dds");
        const Format& read_format = find_format(texture.format);
        expect_unit_range(read_format.decode(texture, CodecContext{1, 1}), "decoded mutation");
      } catch (const Error&) {
        // expected for most mutations
      }
    }
  }
}

}  // namespace
}  // namespace blocklab
