// `munkberg` robustness: random 128-bit blocks of random texture sizes decode through the Format without crashing to
// finite, non-negative values (and identically to the reference decoder); malformed shape side data is a
// blocklab::Error, never a crash; the encoder survives extreme inputs (zeros, the half range's extremes, odd sizes,
// single-channel and RGBA sources) and its output decodes. Run under BLOCKLAB_SANITIZE=ON to catch memory errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "core/error.h"
#include "formats/munkberg/munkberg_block.h"
#include "formats/munkberg/munkberg_modes.h"
#include "formats/registry.h"

namespace blocklab {
namespace {

const Format& munkberg() { return find_format("munkberg"); }

void expect_finite_non_negative(const Image& image, const std::string& context) {
  for (float value : image.pixels) {
    ASSERT_TRUE(std::isfinite(value)) << context;
    ASSERT_GE(value, 0.0f) << context;
  }
}

TEST(MunkbergFuzz, RandomBlocksOfRandomSizesDecodeToFiniteNonNegativeValues) {
  std::mt19937_64 random(61);
  for (int trial = 0; trial < 80; ++trial) {
    EncodedTexture texture;
    texture.format = "munkberg";
    texture.options = resolve_format_options(munkberg(), {});
    texture.width = 1 + static_cast<int>(random() % 90);
    texture.height = 1 + static_cast<int>(random() % 90);
    texture.channels = trial % 3 == 0 ? 4 : (trial % 3 == 1 ? 3 : 1);
    texture.block_bytes = munkberg().block_bytes(texture.options);
    const BlockGrid grid(texture.width, texture.height);
    texture.blocks.resize(grid.block_count() * static_cast<std::size_t>(texture.block_bytes));
    for (auto& byte : texture.blocks) byte = static_cast<std::uint8_t>(random() & 0xFFu);
    // Half of the trials carry the (default) shape set as side data, half rely on the default.
    if (trial % 2 == 0)
      texture.side_data[munkberg::kShapeSideDataKey] = munkberg::shape_set_to_side_data(munkberg::default_shape_set());
    // Every mode's blocks occur (the selector is random); a third of the trials decode ext_s3tc in logyuv.
    munkberg::ModeContext mode_context;
    if (trial % 3 == 2) {
      texture.side_data[munkberg::kExtS3tcSpaceKey] = {1.0};
      mode_context.ext_s3tc_space = munkberg::ExtS3tcSpace::logyuv;
    }
    const Image decoded = munkberg().decode(texture, CodecContext{0, 1});
    expect_finite_non_negative(decoded, "trial " + std::to_string(trial));
    for (std::size_t b = 0; b < grid.block_count(); ++b) {
      const std::uint8_t* bytes = texture.blocks.data() + b * munkberg::kBlockBytes;
      const BlockTexels fast = munkberg::decode_any_block(bytes, mode_context);
      const BlockTexels reference = munkberg::reference_decode_any_block(bytes, mode_context);
      ASSERT_EQ(0, std::memcmp(fast.rgba, reference.rgba, sizeof fast.rgba)) << "trial " << trial << " block " << b;
    }
  }
}

TEST(MunkbergFuzz, MalformedShapeSideDataIsAnErrorNotACrash) {
  std::mt19937_64 random(62);
  EncodedTexture texture;
  texture.format = "munkberg";
  texture.options = resolve_format_options(munkberg(), {});
  texture.width = texture.height = 8;
  texture.block_bytes = munkberg::kBlockBytes;
  texture.blocks.assign(4 * munkberg::kBlockBytes, 0x5Au);
  const std::vector<double> good = munkberg::shape_set_to_side_data(munkberg::default_shape_set());
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<double> values = good;
    switch (trial % 3) {
      case 0: values.resize(random() % good.size()); break;                       // truncated
      case 1: values[random() % values.size()] = static_cast<double>(random() % 7) - 3.0; break;   // any value
      default: values.push_back(1.0); break;                                         // too long
    }
    texture.side_data[munkberg::kShapeSideDataKey] = values;
    try {
      const Image decoded = munkberg().decode(texture, CodecContext{1, 1});
      expect_finite_non_negative(decoded, "trial " + std::to_string(trial));
    } catch (const Error&) {
      // Rejected with a message: fine.
    }
  }
}

TEST(MunkbergFuzz, EncoderSurvivesExtremeInputsAndItsOutputDecodes) {
  std::mt19937_64 random(63);
  const float extremes[] = {0.0f, 0x1p-24f, 0x1p-14f, 1.0f, 65504.0f, 1e-30f, 3.0e5f};
  for (int trial = 0; trial < 12; ++trial) {
    const int width = 1 + static_cast<int>(random() % 9), height = 1 + static_cast<int>(random() % 9);
    Image image(width, height, trial % 3 == 0 ? 1 : (trial % 3 == 1 ? 3 : 4));
    for (std::size_t i = 0; i < image.texel_count(); ++i)
      for (int c = 0; c < 4; ++c)
        image.pixels[4 * i + c] = extremes[random() % (sizeof extremes / sizeof extremes[0])];
    const EncodedTexture texture =
        munkberg().encode(image, resolve_format_options(munkberg(), {}), CodecContext{1, 1});
    const Image decoded = munkberg().decode(texture, CodecContext{1, 1});
    expect_finite_non_negative(decoded, "trial " + std::to_string(trial));
    // Every mode competing (section 6), both extended-S3TC spaces: output decodes to finite, non-negative values.
    const EncodedTexture all = munkberg().encode(
        image,
        resolve_format_options(munkberg(), {{"modes", "all"}, {"ext_s3tc_space", trial % 2 == 0 ? "rgb" : "logyuv"}}),
        CodecContext{1, 1});
    expect_finite_non_negative(munkberg().decode(all, CodecContext{1, 1}), "modes=all trial " + std::to_string(trial));
    // True-black source texels (all three channels 0) decode to black.
    for (std::size_t i = 0; i < image.texel_count(); ++i) {
      const float* s = &image.pixels[4 * i];
      if (s[0] == 0.0f && s[1] == 0.0f && s[2] == 0.0f && image.channels != 1) {
        for (int c = 0; c < 3; ++c) EXPECT_EQ(decoded.pixels[4 * i + c], 0.0f) << "trial " << trial << " texel " << i;
      }
    }
  }
}

}  // namespace
}  // namespace blocklab
