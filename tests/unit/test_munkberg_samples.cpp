// `munkberg` bit-exactness on real images: every block the encoder emits for the bundled HDR samples (samples/hdr/*)
// decodes bit-identically with the fast decoder (decode_block<double>) and the spec-literal reference decoder,
// block_modes records each block's mode bit, and both modes are used.
#include <gtest/gtest.h>

#include <cstring>

#include "core/image_io.h"
#include "core/input_policy.h"
#include "formats/munkberg/munkberg_block.h"
#include "formats/registry.h"

namespace blocklab::munkberg {
namespace {

const Format& format() { return find_format("munkberg"); }
FormatOptions options(const FormatOptions& given = {}) { return resolve_format_options(format(), given); }

Image sample(const std::string& name) {
  Image image = read_image(std::string(BLOCKLAB_TEST_SAMPLES) + "/hdr/" + name);
  apply_input_policy(image, InputPolicy::clamp, name);
  return image;
}

TEST(MunkbergSamples, EveryEmittedBlockOfTheSamplesDecodesLikeTheReferenceDecoder) {
  for (const std::string name : {"Desk.exr", "blender_world_sunset.exr", "hdr-rgb-arboretum.hdr"}) {
    const Image image = sample(name);
    // The shape modes (the paper's format); every mode's blocks: test_munkberg_modes.cpp.
    const EncodedTexture texture = format().encode(image, options({{"modes", "both"}}), CodecContext{0, 1});
    ASSERT_EQ(texture.block_modes.size() * kBlockBytes, texture.blocks.size());
    const ShapeSet shapes = shape_set_of(texture.side_data);
    std::size_t shape_one = 0;
    for (std::size_t b = 0; b < texture.block_modes.size(); ++b) {
      const std::uint8_t* bytes = texture.blocks.data() + b * kBlockBytes;
      const BlockTexels fast = decode_params(unpack_block(bytes), shapes);
      const BlockTexels reference = reference_decode_block(bytes, shapes);
      ASSERT_EQ(0, std::memcmp(fast.rgba, reference.rgba, sizeof fast.rgba)) << name << " block " << b;
      ASSERT_EQ(texture.block_modes[b], static_cast<int>(block_mode_of(bytes))) << name << " block " << b;
      shape_one += texture.block_modes[b];
    }
    // Both modes are used on real images (section 5: they complement each other).
    EXPECT_GT(shape_one, 0u) << name;
    EXPECT_LT(shape_one, texture.block_modes.size()) << name;
  }
}

}  // namespace
}  // namespace blocklab::munkberg
