// The DDS form of `mavridis` (formats/mavridis/README.md, "DDS output"): every standard texture its gpu_textures()
// returns (BC3 / BC7 coefficient textures, BC1 detail levels, the BC4 luminance of 5 bpp), written with write_dds,
// decodes in Debian's Pillow (python3-pil DdsImagePlugin, tests/tools/pil_decode_dds.py) to the texels blocklab's
// own decoder of that format gives, byte for byte: Pillow interpolates the palettes in integers and truncates
// (e.g. (2 c0 + c1) / 3), so every byte it writes is floor(255 v) of blocklab's exact-fraction value v (BC7 values are
// k / 255, so there floor(255 v) = k). The test counts the bytes that break this and requires none.
// Skips when Pillow or the shared Kodak images are absent.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "formats/common/dds.h"
#include "formats/registry.h"
#include "pillow_dds.h"
#include "../unit/test_s3tc_helpers.h"

namespace blocklab {
namespace {

namespace fs = std::filesystem;

TEST(MavridisDds, EveryGpuTextureDecodesInPillowAsInBlocklab) {
  if (!pillow_dds::available()) GTEST_SKIP() << "/usr/bin/python3 with PIL.DdsImagePlugin not available";
  const Image image = s3tc_test::real_crop("kodak/kodim03.png", 250, 150, 101, 75);
  if (image.width == 0) GTEST_SKIP() << "shared LDR images not found under " << BLOCKLAB_TEST_SHARED_DATA;
  const fs::path directory = fs::temp_directory_path() / ("blocklab_test_mavridis_dds_" + std::to_string(::getpid()));
  fs::create_directories(directory);
  const Format& mavridis = find_format("mavridis");
  const std::vector<std::map<std::string, std::string>> variants = {
      {{"bpp", "3"}}, {{"bpp", "5"}}, {{"bpp", "2.25"}, {"packing", "bc7"}}, {{"bpp", "2"}, {"levels", "2"}}};
  int textures_checked = 0;
  for (const auto& given : variants) {
    FormatOptions options = given;
    options["preset"] = "fast";
    const EncodedTexture texture =
        mavridis.encode(image, resolve_format_options(mavridis, options), CodecContext{1, 1});
    for (const GpuTexture& gpu : mavridis.gpu_textures(texture)) {
      const Format& format = find_format(gpu.texture.format);
      const Image ours = format.decode(gpu.texture, CodecContext{1, 1});
      const fs::path dds = directory / (gpu.suffix + ".dds"), raw = directory / (gpu.suffix + ".rgba");
      write_dds(dds.string(), gpu.texture);
      const std::string command = pillow_dds::decode_command(dds, raw);
      ASSERT_EQ(std::system(command.c_str()), 0) << command;
      const std::vector<std::uint8_t> rgba = pillow_dds::read_bytes(raw);
      ASSERT_EQ(rgba.size(), ours.texel_count() * 4) << gpu.suffix << " " << gpu.texture.format;
      // BC4 decodes to one channel (Pillow: grey), BC1 / BC7 here to RGB (BC7 alpha is 255), BC3 to RGBA.
      const int channels = gpu.texture.format == "bc4" ? 1 : (gpu.texture.format == "bc3" ? 4 : 3);
      std::size_t differing = 0, checked = 0;
      for (std::size_t i = 0; i < ours.texel_count(); ++i)
        for (int c = 0; c < channels; ++c) {
          // The margin absorbs the float rounding of v = k / (255 d); it is far below one step 1 / (255 d).
          const int truncated = static_cast<int>(std::floor(255.0 * ours.pixels[i * 4 + c] + 1e-3));
          differing += truncated != rgba[i * 4 + c] ? 1 : 0;
          ++checked;
        }
      EXPECT_EQ(differing, 0u) << gpu.suffix << " " << gpu.texture.format << ": bytes where Pillow differs from floor(255 v)";
      std::printf("[pillow] mavridis %s %s %dx%d: %zu of %zu bytes equal floor(255 v)\n", gpu.suffix.c_str(),
                  gpu.texture.format.c_str(), gpu.texture.width, gpu.texture.height, checked - differing, checked);
      ++textures_checked;
    }
  }
  EXPECT_EQ(textures_checked, 3 + 3 + 3 + 2);
  fs::remove_all(directory);
}

}  // namespace
}  // namespace blocklab
