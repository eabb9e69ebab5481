// Independent-decoder check of BC6H: Debian 12's Pillow 9.4 (python3-pil DdsImagePlugin, via
// tests/tools/pil_decode_dds.py) decodes DX10 dxgiFormat 95 (BC6H_UF16) and 96 (BC6H_SF16) to 8-bit RGB: each half
// value clamped to [0, 1] and truncated, floor(255 x). Measured against our decoder (2026-11-27): UF16 agrees with
// that rule except in 0.03-2% of samples, which Pillow decodes one half-float step lower: it interpolates without
// the +32 rounding term of ((64 - w) E0 + w E1 + 32) >> 6 (our decoder without that term matched Pillow on all 107,082
// in-range samples of 4,096 random blocks); SF16 agrees on untransformed modes and on blocks with non-negative endpoints, but not on
// transformed-mode blocks whose endpoints wrap negative (Pillow does not sign-extend the transformed endpoints, which
// the KDFS and Direct3D decoders do), so random SF16 blocks are drawn from the untransformed modes 3 and 30 only.
// Checked: blocklab's encodes of the bundled HDR crops (scaled into [0, 1]) and random blocks. Pillow missing ->
// GTEST_SKIP.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>

#include "core/image_io.h"
#include "core/input_policy.h"
#include "formats/bc6h/bc6h_half.h"
#include "formats/common/dds.h"
#include "formats/registry.h"
#include "pillow_dds.h"

namespace blocklab {
namespace {

namespace fs = std::filesystem;

struct Agreement {
  std::size_t samples = 0, one_step_lower = 0, other = 0;
};

class Bc6hPillow : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!pillow_dds::available()) GTEST_SKIP() << "/usr/bin/python3 with PIL.DdsImagePlugin not available";
    directory_ = fs::temp_directory_path() / ("blocklab_test_bc6h_pillow_" + std::to_string(::getpid()) + "_" +
                                              ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(directory_);
  }
  void TearDown() override { fs::remove_all(directory_); }

  // Pillow's RGBA8 decode of `texture` written as DDS.
  std::vector<std::uint8_t> pillow_decode(const EncodedTexture& texture) {
    const fs::path dds = directory_ / "texture.dds";
    const fs::path raw = directory_ / "texture.rgba";
    write_dds(dds.string(), texture);
    const std::string command = pillow_dds::decode_command(dds, raw, (directory_ / "pil.txt").string());
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
    return pillow_dds::read_bytes(raw);
  }

  // Pillow's byte against floor(255 clamp(x, 0, 1)) for our decoded x >= 0 (negative values: see the header), or
  // the same of the half value one step below x (Pillow's interpolation without the rounding term).
  static Agreement compare(const Image& ours, const std::vector<std::uint8_t>& rgba) {
    Agreement result;
    const auto byte_of = [](double value) { return std::floor(255.0 * std::min(value, 1.0)); };
    for (std::size_t i = 0; i < ours.texel_count(); ++i)
      for (int c = 0; c < 3; ++c) {
        const float value = ours.pixels[i * 4 + c];
        if (!(value >= 0.0f)) continue;
        const std::uint16_t bits = bc6h::float_to_half_bits(value);   // exact: value is a decoded half
        const double lower = bc6h::half_bits_to_float(static_cast<std::uint16_t>(bits == 0 ? 0 : bits - 1));
        const double pillow = rgba[i * 4 + c];
        ++result.samples;
        if (pillow == byte_of(value)) continue;
        if (pillow == byte_of(lower))
          ++result.one_step_lower;
        else
          ++result.other;
      }
    return result;
  }

  static void expect_agreement(const Agreement& result, const std::string& label) {
    ASSERT_GT(result.samples, 0u) << label;
    EXPECT_EQ(result.other, 0u) << label;
    std::printf("[pillow] %s: %zu samples, %zu equal floor(255 x) of the half one step lower, %zu otherwise different\n",
                label.c_str(), result.samples, result.one_step_lower, result.other);
  }

  fs::path directory_;
};

TEST_F(Bc6hPillow, PillowDecodesOurEncodesOfTheBundledHdrCropsLikeOurDecoder) {
  for (const char* name : {"bc6h", "bc6h_sf"}) {
    const Format& format = find_format(name);
    for (const char* file : {"hdr/Desk.exr", "hdr/hdr-rgb-arboretum.hdr", "hdr/blender_world_sunset.exr"}) {
      const std::string path = std::string(BLOCKLAB_TEST_SAMPLES) + "/" + file;
      Image image = read_image(path);
      apply_input_policy(image, InputPolicy::clamp, path);
      image = crop_image(image, 0, 0, std::min(image.width, 96), std::min(image.height, 80));
      // Into [0, 1], where Pillow's 8-bit output can show differences.
      float peak = 0.0f;
      for (std::size_t i = 0; i < image.texel_count(); ++i)
        for (int c = 0; c < 3; ++c) peak = std::max(peak, image.pixels[i * 4 + c]);
      for (float& value : image.pixels) value = peak > 0.0f ? value / peak : value;
      const EncodedTexture texture = format.encode(image, resolve_format_options(format, {}), CodecContext{0, 1});
      const std::vector<std::uint8_t> rgba = pillow_decode(texture);
      ASSERT_EQ(rgba.size(), image.texel_count() * 4) << name << " " << file;
      expect_agreement(compare(format.decode(texture, CodecContext{0, 1}), rgba), std::string(name) + " " + file);
    }
  }
}

TEST_F(Bc6hPillow, PillowDecodesRandomBlocksLikeOurDecoder) {
  std::mt19937_64 random(95);
  for (const char* name : {"bc6h", "bc6h_sf"}) {
    const bool is_signed = std::string(name) == "bc6h_sf";
    const Format& format = find_format(name);
    EncodedTexture texture;
    texture.format = name;
    texture.options = resolve_format_options(format, {});
    texture.width = texture.height = 256;
    texture.channels = 3;
    texture.block_bytes = 16;
    texture.blocks.resize(64 * 64 * 16);
    for (std::size_t block = 0; block < 64 * 64; ++block) {
      std::uint8_t* bytes = texture.blocks.data() + block * 16;
      for (int i = 0; i < 16; ++i) bytes[i] = static_cast<std::uint8_t>(random());
      if (is_signed) bytes[0] = static_cast<std::uint8_t>((bytes[0] & ~31) | (block % 2 ? 3 : 30));
    }
    const std::vector<std::uint8_t> rgba = pillow_decode(texture);
    ASSERT_EQ(rgba.size(), 256u * 256u * 4u) << name;
    expect_agreement(compare(format.decode(texture, CodecContext{0, 1}), rgba), std::string(name) + " random blocks");
  }
}

}  // namespace
}  // namespace blocklab
