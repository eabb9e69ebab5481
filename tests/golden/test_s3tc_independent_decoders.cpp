// Independent-decoder checks: BC1/BC3/BC4/BC7 DDS files written by blocklab from real Kodak / texture
// crops decode with Debian's Pillow (python3-pil DdsImagePlugin, via tests/tools/pil_decode_dds.py) and NVIDIA Texture Tools 2.0's
// `nvdecompress` (which writes <input stem>.tga next to the input) to the same pixels as blocklab's reference
// decoding, within its documented relation to vendor decoders (formats/common/s3tc_common.h): every 8-bit
// channel within 1 LSB of 255 * our exact-fraction value, and exactly equal on endpoint texels. A tool that is not
// installed makes its test GTEST_SKIP; the shared images being absent does too.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/error.h"
#include "formats/common/dds.h"
#include "formats/registry.h"
#include "pillow_dds.h"
#include "../unit/test_s3tc_helpers.h"

namespace blocklab {
namespace {

namespace fs = std::filesystem;

bool tool_exists(const std::string& command) {
  return std::system(("command -v " + command + " > /dev/null 2>&1").c_str()) == 0;
}

class IndependentDecoders : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = fs::temp_directory_path() / ("blocklab_test_s3tc_decoders_" + std::to_string(::getpid()) + "_" +
                                              ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(directory_);
  }
  void TearDown() override { fs::remove_all(directory_); }

  // Real crops: photographs (one with a size that is not a multiple of 4) and textures (one with alpha).
  static std::vector<std::pair<std::string, Image>> crops() {
    std::vector<std::pair<std::string, Image>> result;
    const struct { const char* file; int x, y, w, h; } specs[] = {
        {"kodak/kodim01.png", 100, 100, 128, 96}, {"kodak/kodim03.png", 250, 150, 101, 75},
        {"kodak/kodim20.png", 0, 0, 64, 64},      {"textures/ldr-rgba-base.png", 300, 300, 96, 96},
        {"textures/ldr-rgb-diffuse.png", 1000, 1000, 64, 64},
    };
    for (const auto& spec : specs) {
      Image crop = s3tc_test::real_crop(spec.file, spec.x, spec.y, spec.w, spec.h);
      if (crop.width > 0) result.emplace_back(spec.file, std::move(crop));
    }
    return result;
  }

  fs::path directory_;
};

struct Comparison {
  int max_difference = 0;
  std::size_t samples = 0, differing = 0;
};

// Compares 8-bit RGBA (row-major, top row first) with our decode; channels [0, channel_count).
Comparison compare(const Image& ours, const std::vector<std::uint8_t>& rgba, int channel_count) {
  Comparison result;
  for (std::size_t i = 0; i < ours.texel_count(); ++i)
    for (int c = 0; c < channel_count; ++c) {
      const double exact = 255.0 * ours.pixels[i * 4 + c];
      const double difference = std::fabs(exact - rgba[i * 4 + c]);
      // "within 1 LSB": strictly less than one code value from the exact fraction (rounding or truncation).
      const int lsb = difference < 1e-3 ? 0 : (difference < 1.0 - 1e-6 ? 1 : static_cast<int>(std::ceil(difference)));
      result.max_difference = std::max(result.max_difference, lsb);
      result.differing += lsb != 0;
      ++result.samples;
    }
  return result;
}

// Uncompressed 32-bit TGA (what nvdecompress writes) -> RGBA8 top row first. Empty on anything else.
std::vector<std::uint8_t> read_tga(const fs::path& path, int& width, int& height) {
  const std::vector<std::uint8_t> bytes = pillow_dds::read_bytes(path);
  if (bytes.size() < 18 || bytes[2] != 2 || bytes[16] != 32) return {};
  width = bytes[12] | (bytes[13] << 8);
  height = bytes[14] | (bytes[15] << 8);
  const std::size_t offset = 18 + bytes[0];
  if (bytes.size() < offset + static_cast<std::size_t>(width) * height * 4) return {};
  const bool top_down = (bytes[17] & 0x20) != 0;
  std::vector<std::uint8_t> rgba(static_cast<std::size_t>(width) * height * 4);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t source = offset + (static_cast<std::size_t>(top_down ? y : height - 1 - y) * width + x) * 4;
      const std::size_t target = (static_cast<std::size_t>(y) * width + x) * 4;
      rgba[target + 0] = bytes[source + 2];   // BGRA -> RGBA
      rgba[target + 1] = bytes[source + 1];
      rgba[target + 2] = bytes[source + 0];
      rgba[target + 3] = bytes[source + 3];
    }
  return rgba;
}

TEST_F(IndependentDecoders, PillowDecodesOurBc1Bc3Bc4Bc7WithinOneLsb) {
  if (!pillow_dds::available()) GTEST_SKIP() << "/usr/bin/python3 with PIL.DdsImagePlugin not available";
  const auto images = crops();
  if (images.empty()) GTEST_SKIP() << "shared LDR images not found under " << BLOCKLAB_TEST_SHARED_DATA;
  // BC1: RGB only (Pillow decodes DXT1 as BC1 with punch-through alpha, so the 3-colour black has alpha 0).
  const std::pair<const char*, int> formats[] = {{"bc1", 3}, {"bc3", 4}, {"bc4", 1}, {"bc7", 4}};
  for (const auto& [format_name, channels] : formats) {
    bool registered = false;
    for (const Format* f : all_formats()) registered |= f->name() == format_name;
    ASSERT_TRUE(registered) << format_name;
    const Format& format = find_format(format_name);
    for (const auto& [file, image] : images) {
      const EncodedTexture texture = format.encode(image, resolve_format_options(format, {}), CodecContext{0, 1});
      const Image ours = format.decode(texture, CodecContext{0, 1});
      const fs::path dds = directory_ / (std::string(format_name) + ".dds");
      const fs::path raw = directory_ / (std::string(format_name) + ".rgba");
      write_dds(dds.string(), texture);
      const std::string command = pillow_dds::decode_command(dds, raw, (directory_ / "pil.txt").string());
      ASSERT_EQ(std::system(command.c_str()), 0) << format_name << " " << file << ": " << command;
      const std::vector<std::uint8_t> rgba = pillow_dds::read_bytes(raw);
      ASSERT_EQ(rgba.size(), ours.texel_count() * 4) << format_name << " " << file << ": Pillow size differs";
      const Comparison result = compare(ours, rgba, channels);
      EXPECT_LE(result.max_difference, 1) << format_name << " " << file;
      std::printf("[pillow] %s %s: %zu of %zu samples differ by 1 LSB, max %d\n", format_name, file.c_str(),
                  result.differing, result.samples, result.max_difference);
    }
  }
}

TEST_F(IndependentDecoders, NvdecompressDecodesOurBc1Bc3WithinOneLsb) {
  if (!tool_exists("nvdecompress")) GTEST_SKIP() << "nvdecompress (libnvtt-bin) not installed";
  const auto images = crops();
  if (images.empty()) GTEST_SKIP() << "shared LDR images not found under " << BLOCKLAB_TEST_SHARED_DATA;
  for (const auto& [format_name, channels] : {std::pair<const char*, int>{"bc1", 3}, {"bc3", 4}}) {
    const Format& format = find_format(format_name);
    for (const auto& [file, image] : images) {
      const EncodedTexture texture = format.encode(image, resolve_format_options(format, {}), CodecContext{0, 1});
      const Image ours = format.decode(texture, CodecContext{0, 1});
      const fs::path dds = directory_ / (std::string(format_name) + ".dds");
      const fs::path tga = directory_ / (std::string(format_name) + ".tga");   // nvdecompress: <stem>.tga beside it
      fs::remove(tga);
      write_dds(dds.string(), texture);
      const std::string command = "cd '" + directory_.string() + "' && nvdecompress '" + dds.string() + "' > /dev/null 2>&1";
      ASSERT_EQ(std::system(command.c_str()), 0) << command;
      int width = 0, height = 0;
      const std::vector<std::uint8_t> decoded = read_tga(tga, width, height);
      ASSERT_FALSE(decoded.empty()) << "nvdecompress wrote no readable " << tga;
      // NVTT decodes whole blocks: crop its padded output to the true size.
      ASSERT_GE(width, image.width);
      ASSERT_GE(height, image.height);
      std::vector<std::uint8_t> rgba(ours.texel_count() * 4);
      for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
          for (int c = 0; c < 4; ++c)
            rgba[(static_cast<std::size_t>(y) * image.width + x) * 4 + c] =
                decoded[(static_cast<std::size_t>(y) * width + x) * 4 + c];
      const Comparison result = compare(ours, rgba, channels == 4 && image.channels == 4 ? 4 : 3);
      EXPECT_LE(result.max_difference, 1) << format_name << " " << file;
      std::printf("[nvdecompress] %s %s: %zu of %zu samples differ by 1 LSB, max %d\n", format_name, file.c_str(),
                  result.differing, result.samples, result.max_difference);
    }
  }
}

}  // namespace
}  // namespace blocklab
