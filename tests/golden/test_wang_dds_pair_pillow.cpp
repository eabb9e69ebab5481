// The `wang` texture as the paper's two DXT5 textures (Wang et al. 2007 section 3.3; formats/wang/wang_dds.h) read by
// an independent decoder: each bundled HDR sample (a 64x48 crop, and a 37x21 crop whose sides are not multiples of 4)
// is encoded with the default wang options, its Format::gpu_textures (tex0, tex1) are written as DDS files, and
// Debian's Pillow (python3-pil DdsImagePlugin, via tests/tools/pil_decode_dds.py) decodes each file to RGBA8.
//
// Exactness: Pillow 9 decodes BC3 with the 8-bit bit-replicated 565 endpoints and integer division ((2 c0 + c1) / 3,
// ((8 - i) a0 + (i - 1) a1) / 7, ...), so every byte it writes is floor(255 v) of blocklab's exact-fraction value v
// (formats/common/s3tc_common.h). The test requires that equality on every channel of every texel of both textures
// (bit-exact RGBA8), with v from blocklab's bc3 decoder of the DDS file read back; and the DDS files read back are
// the bytes Format::gpu_textures returned, which join back into the encoded wang blocks.
// Pillow missing makes the test GTEST_SKIP.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "core/image_io.h"
#include "core/input_policy.h"
#include "formats/common/dds.h"
#include "formats/registry.h"
#include "pillow_dds.h"

namespace blocklab {
namespace {

namespace fs = std::filesystem;

// Pillow's integer-division byte of an exact BC3 fraction v = k / (255 d): floor(255 v). The margin absorbs the float
// rounding of v (one ulp of 255 v is far below 1e-3; the next integer is at least 1 / 7 away from any fraction).
int truncated_byte(float value) { return static_cast<int>(std::floor(255.0 * value + 1e-3)); }

class WangDdsPairPillow : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = fs::temp_directory_path() / ("blocklab_test_wang_dds_pair_" + std::to_string(::getpid()));
    fs::create_directories(directory_);
  }
  void TearDown() override { fs::remove_all(directory_); }
  fs::path directory_;
};

TEST_F(WangDdsPairPillow, PillowDecodesBothDxt5TexturesOfEncodedHdrCropsBitExactly) {
  if (!pillow_dds::available()) GTEST_SKIP() << "/usr/bin/python3 with PIL.DdsImagePlugin not available";
  const Format& wang = find_format("wang");
  const Format& bc3 = find_format("bc3");
  const struct { const char* file; int x, y, w, h; } crops[] = {
      {"hdr/Desk.exr", 0, 0, 64, 48},
      {"hdr/hdr-rgb-arboretum.hdr", 0, 0, 64, 48},
      {"hdr/blender_world_sunset.exr", 0, 0, 64, 48},
      {"hdr/hdr-rgb-arboretum.hdr", 11, 5, 37, 21},
  };
  int textures_checked = 0;
  for (const auto& spec : crops) {
    const std::string path = std::string(BLOCKLAB_TEST_SAMPLES) + "/" + spec.file;
    Image image = read_image(path);
    apply_input_policy(image, InputPolicy::clamp, path);
    image = crop_image(image, spec.x, spec.y, std::min(image.width - spec.x, spec.w),
                       std::min(image.height - spec.y, spec.h));
    const std::string label = std::string(spec.file) + " " + std::to_string(image.width) + "x" +
                              std::to_string(image.height);
    const EncodedTexture texture = wang.encode(image, resolve_format_options(wang, {}), CodecContext{1, 1});
    const std::vector<GpuTexture> textures = wang.gpu_textures(texture);
    ASSERT_EQ(textures.size(), 2u) << label;
    EXPECT_EQ(textures[0].suffix, "tex0");
    EXPECT_EQ(textures[1].suffix, "tex1");
    std::vector<std::uint8_t> joined;   // tex0 and tex1 blocks interleaved again: the wang blocks
    std::vector<EncodedTexture> read_back;
    for (const GpuTexture& gpu : textures) {
      ASSERT_EQ(gpu.texture.format, "bc3") << label;
      const fs::path dds = directory_ / (gpu.suffix + ".dds");
      const fs::path raw = directory_ / (gpu.suffix + ".rgba");
      write_dds(dds.string(), gpu.texture);
      read_back.push_back(read_dds(dds.string()));
      EXPECT_EQ(read_back.back().blocks, gpu.texture.blocks) << label << " " << gpu.suffix;
      const std::string command = pillow_dds::decode_command(dds, raw, (directory_ / "pil.txt").string());
      ASSERT_EQ(std::system(command.c_str()), 0) << label << " " << gpu.suffix << ": " << command;
      const std::vector<std::uint8_t> rgba = pillow_dds::read_bytes(raw);
      const Image ours = bc3.decode(read_back.back(), CodecContext{1, 1});
      ASSERT_EQ(ours.width, image.width);
      ASSERT_EQ(ours.height, image.height);
      ASSERT_EQ(rgba.size(), ours.texel_count() * 4) << label << " " << gpu.suffix << ": Pillow size differs";
      std::size_t differing = 0;
      for (std::size_t i = 0; i < ours.texel_count() * 4; ++i)
        differing += truncated_byte(ours.pixels[i]) != rgba[i];
      EXPECT_EQ(differing, 0u) << label << " " << gpu.suffix << ": bytes where Pillow differs from floor(255 v)";
      ++textures_checked;
    }
    for (std::size_t block = 0; block * 32 < texture.blocks.size(); ++block)
      for (int half = 0; half < 2; ++half)
        joined.insert(joined.end(), read_back[half].blocks.begin() + block * 16,
                      read_back[half].blocks.begin() + block * 16 + 16);
    EXPECT_EQ(joined, texture.blocks) << label << ": tex0 / tex1 blocks do not interleave into the wang blocks";
  }
  EXPECT_EQ(textures_checked, 8);
}

}  // namespace
}  // namespace blocklab
